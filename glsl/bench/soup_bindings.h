// Binding points of the triangle-soup benchmark (apps/bench/soup.cpp, Figure 2 of the paper),
// shared by its C++ and its shaders. Only the soup's own programs use them.
#ifndef SUBDFIT_SOUP_BINDINGS_H
#define SUBDFIT_SOUP_BINDINGS_H

#define SUBDFIT_SOUP_SSBO_POSITIONS 0           // 9 floats per triangle: corners (x, y, z), clip space
#define SUBDFIT_SOUP_SSBO_COLORS 1              // 3 floats per triangle: RGB
#define SUBDFIT_SOUP_SSBO_TRIANGLE_DELTA 2      // per-pixel: Σ Δ_p per triangle; full-image: 256 slots
#define SUBDFIT_SOUP_SSBO_GRADIENT_POSITIONS 3
#define SUBDFIT_SOUP_SSBO_GRADIENT_COLORS 4

#define SUBDFIT_SOUP_UNIT_COLOR_PLUS 0
#define SUBDFIT_SOUP_UNIT_COLOR_MINUS 1
#define SUBDFIT_SOUP_UNIT_TRIANGLE_PLUS 2
#define SUBDFIT_SOUP_UNIT_TRIANGLE_MINUS 3
#define SUBDFIT_SOUP_UNIT_TARGET 4

#define SUBDFIT_SOUP_ATTACHMENT_COLOR 0
#define SUBDFIT_SOUP_ATTACHMENT_TRIANGLE 1

// Sign-stream salts of the two parameter groups (perturb.comp hashes with seed ^ salt).
#define SUBDFIT_SOUP_SEED_POSITIONS 0u
#define SUBDFIT_SOUP_SEED_COLORS 0x2c1b3c6du

#endif
