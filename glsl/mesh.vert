layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
#if defined(SUBDFIT_SHADING_UNLIT) || defined(SUBDFIT_SHADING_LAMBERT) || defined(SUBDFIT_SHADING_PBR)
#define SUBDFIT_MATERIAL_ATTRIBUTES
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inColor;
out vec2 vUv;
out vec4 vColor;
#endif

out vec3 vWorldPosition;
out vec3 vWorldNormal;

uniform mat4 uViewProjection;

void main() {
    vWorldPosition = inPosition;
    vWorldNormal = inNormal;
#ifdef SUBDFIT_MATERIAL_ATTRIBUTES
    vUv = inUv;
    vColor = inColor;
#endif
    gl_Position = uViewProjection * vec4(inPosition, 1.0);
}
