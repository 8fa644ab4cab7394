// A supersampled render as a viewer shows it (scene::TargetSet): each pixel the mean of its
// uFactor × uFactor block of samples in `fine`, summed row by row as the samples lie.
layout(binding = SUBDFIT_IMAGE_FINE, rgba32f) readonly uniform image2D fine;

uniform int uFactor;

vec4 filteredPixel(ivec2 pixel) {
    ivec2 first = pixel * uFactor;
    float weight = 1.0 / float(uFactor * uFactor);
    vec4 mean = vec4(0.0);
    for (int y = 0; y < uFactor; ++y)
        for (int x = 0; x < uFactor; ++x) mean += weight * imageLoad(fine, first + ivec2(x, y));
    return mean;
}
