// The reference (a plain triangle mesh) with exactly the shading of the cage's limit surface.
#include "bindings.h"
#include "shading.glsl"

in vec3 vWorldPosition;
in vec3 vWorldNormal;

layout(location = SUBDFIT_ATTACHMENT_COLOR) out vec4 outColor;
layout(location = SUBDFIT_ATTACHMENT_FACE_ID) out int outFaceId;
layout(location = SUBDFIT_ATTACHMENT_PATCH_UV) out vec2 outPatchUv;

uniform mat4 uView;
uniform vec3 uEye;

void main() {
    vec3 n = dot(vWorldNormal, vWorldNormal) > 0.0 ? normalize(vWorldNormal) : vec3(0.0, 0.0, 1.0);
    if (dot(n, uEye - vWorldPosition) < 0.0) n = -n;
    outColor = vec4(shadeLambert(normalize(mat3(uView) * n)), 1.0);
    outFaceId = gl_PrimitiveID;
    outPatchUv = vec2(0.0);
}
