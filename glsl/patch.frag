#include "bindings.h"
#include "shading.glsl"

in vec3 teWorldPosition;
in vec3 teWorldNormal;
flat in int tePtexFace;
in vec2 tePtexUv;

layout(location = SUBDFIT_ATTACHMENT_COLOR) out vec4 outColor;
layout(location = SUBDFIT_ATTACHMENT_FACE_ID) out int outFaceId;
layout(location = SUBDFIT_ATTACHMENT_PATCH_UV) out vec2 outPatchUv;

uniform mat4 uView;
uniform vec3 uEye;

void main() {
    vec3 n = normalize(teWorldNormal);
    if (dot(n, uEye - teWorldPosition) < 0.0) n = -n;  // open surfaces are seen from both sides
    outColor = vec4(shadeLambert(normalize(mat3(uView) * n)), 1.0);
    outFaceId = tePtexFace;
    outPatchUv = tePtexUv;
}
