#pragma once
// A glTF's materials, textures, samplers and images as a MaterialSet (material i of the file is
// material i of the set). What is read: metallic-roughness (factors and textures), normal,
// occlusion and emissive textures, KHR_texture_transform, KHR_materials_emissive_strength,
// KHR_materials_unlit, alpha mode, double-sidedness. Anything that would change the look and is
// not read (a second texture-coordinate set, other material extensions) is named in one
// warning line, never silently dropped.
#include <tiny_gltf.h>

#include <string>

#include "mesh/material.h"

namespace subdfit::mesh::gltf {

// tinygltf's image callback: keeps each image's encoded bytes (from its buffer view, data URI or
// a file the loader has already confined to the glTF's folder) in Image::image, undecoded.
bool keepImageBytes(tinygltf::Image* image, int index, std::string* error, std::string* warning, int, int,
                    const unsigned char* bytes, int size, void*);

// The images the materials use are decoded here (readMaterials), once each: their headers first,
// checked against io::kMaxImagePixelsPerFile together, then their pixels (8-bit RGBA); images
// no material uses stay empty. Throws subdfit::Error naming `path` (and the image) for a texture
// that names a missing image or sampler, an image that does not decode, or too many pixels.
MaterialSet readMaterials(const tinygltf::Model& model, const std::string& path);

}  // namespace subdfit::mesh::gltf
