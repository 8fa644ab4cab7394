#pragma once
#include <glm/vec4.hpp>
#include <vector>

namespace subdfit::fit {

// f = mean over pixels of ‖I_p − T_p‖² (RGB), the loss SGE minimises.
double meanPixelLoss(const std::vector<glm::vec4>& image, const std::vector<glm::vec4>& target);

// PSNR in dB for a peak of 1 over all RGB channels of the whole image (background included).
double psnrFromLoss(double meanPixelLoss);

// Structural similarity (Wang, Bovik, Sheikh & Simoncelli 2004: 11-tap Gaussian window of
// σ = 1.5, C1 = 0.01², C2 = 0.03² for values in [0, 1]) of two width × height RGBA images, its
// map averaged over the RGB channels and over the pixels either image covers (alpha > 0): the
// empty background would otherwise lift every score towards 1. 1 for identical images and for
// two empty ones; lower as local means, contrasts and structure part. Non-finite values count as
// 0. Throws subdfit::Error when the images are not width × height.
double structuralSimilarity(const std::vector<glm::vec4>& image, const std::vector<glm::vec4>& target, int width,
                            int height);

}  // namespace subdfit::fit
