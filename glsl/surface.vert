// A vertex of the tessellated limit surface, as glsl/tessellate.comp evaluated it.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aTangentU;
layout(location = 3) in vec3 aTangentV;
layout(location = 4) in vec2 aPtexUv;
layout(location = 5) in int aPtexFace;

out vec3 teWorldPosition;
out vec3 teWorldNormal;
out vec3 teTangentU;  // ∂P/∂u and ∂P/∂v of the ptex face: the normal map's tangent frame
out vec3 teTangentV;
flat out int tePtexFace;
out vec2 tePtexUv;

uniform mat4 uViewProjection;

void main() {
    teWorldPosition = aPosition;
    teWorldNormal = aNormal;
    teTangentU = aTangentU;
    teTangentV = aTangentV;
    tePtexFace = aPtexFace;
    tePtexUv = aPtexUv;
    gl_Position = uViewProjection * vec4(aPosition, 1.0);
}
