// Lambert under three coloured directional lights fixed to the camera, plus a little ambient.
// On the visible hemisphere the three cosines are independent, so a pixel's colour is close to
// an injective function of its normal: image differences see shape, not just silhouettes.
const vec3 SUBDFIT_LIGHT_DIRS[3] = vec3[3](normalize(vec3(0.6, 0.5, 1.0)),
                                           normalize(vec3(-0.8, 0.3, 0.6)),
                                           normalize(vec3(0.0, -0.9, 0.5)));
const vec3 SUBDFIT_LIGHT_COLORS[3] = vec3[3](vec3(0.85, 0.35, 0.25),
                                             vec3(0.25, 0.75, 0.35),
                                             vec3(0.25, 0.35, 0.85));
const vec3 SUBDFIT_AMBIENT = vec3(0.08);

// nView: unit normal in view space, already turned towards the camera.
vec3 shadeLambert(vec3 nView) {
    vec3 c = SUBDFIT_AMBIENT;
    for (int k = 0; k < 3; ++k) c += SUBDFIT_LIGHT_COLORS[k] * max(dot(nView, SUBDFIT_LIGHT_DIRS[k]), 0.0);
    return c;
}
