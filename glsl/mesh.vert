layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;

out vec3 vWorldPosition;
out vec3 vWorldNormal;

uniform mat4 uViewProjection;

void main() {
    vWorldPosition = inPosition;
    vWorldNormal = inNormal;
    gl_Position = uViewProjection * vec4(inPosition, 1.0);
}
