#pragma once
#include <glm/vec4.hpp>
#include <vector>

namespace subdfit::fit {

// f = mean over pixels of ‖I_p − T_p‖² (RGB), the loss SGE minimises.
double meanPixelLoss(const std::vector<glm::vec4>& image, const std::vector<glm::vec4>& target);

// PSNR in dB for a peak of 1 over all RGB channels of the whole image (background included).
double psnrFromLoss(double meanPixelLoss);

}  // namespace subdfit::fit
