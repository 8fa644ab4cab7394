// Writes the Draco samples in tests/data (not part of the build; run by hand if they must be
// remade):
//   c++ -std=c++17 make_draco_samples.cpp -ldraco -o /tmp/make_draco_samples
//   /tmp/make_draco_samples ..   (from tests/data/tools)
// tetrahedron.drc: a unit tetrahedron (4 points, 4 triangles), lossless positions.
// bad/point_cloud.drc: the same 4 points as a point cloud (not a mesh).
// bad/truncated.drc: tetrahedron.drc cut to half its length.
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <draco/point_cloud/point_cloud_builder.h>

#include <cstdio>
#include <cstdlib>
#include <string>

static const float kCorners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
static const int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

static void save(const std::string& path, const char* data, size_t size) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f || std::fwrite(data, 1, size, f) != size || std::fclose(f) != 0) {
        std::perror(path.c_str());
        std::exit(1);
    }
}

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : ".";
    draco::Encoder encoder;  // no quantization: positions are kept exactly

    draco::TriangleSoupMeshBuilder mesh;
    mesh.Start(4);
    const int pos = mesh.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    for (int f = 0; f < 4; ++f)
        mesh.SetAttributeValuesForFace(pos, draco::FaceIndex(f), kCorners[kFaces[f][0]], kCorners[kFaces[f][1]],
                                       kCorners[kFaces[f][2]]);
    draco::EncoderBuffer meshBuffer;
    if (!encoder.EncodeMeshToBuffer(*mesh.Finalize(), &meshBuffer).ok()) return 1;
    save(dir + "/tetrahedron.drc", meshBuffer.data(), meshBuffer.size());
    save(dir + "/bad/truncated.drc", meshBuffer.data(), meshBuffer.size() / 2);

    draco::PointCloudBuilder cloud;
    cloud.Start(4);
    const int cloudPos = cloud.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    for (int p = 0; p < 4; ++p) cloud.SetAttributeValueForPoint(cloudPos, draco::PointIndex(p), kCorners[p]);
    draco::EncoderBuffer cloudBuffer;
    if (!encoder.EncodePointCloudToBuffer(*cloud.Finalize(false), &cloudBuffer).ok()) return 1;
    save(dir + "/bad/point_cloud.drc", cloudBuffer.data(), cloudBuffer.size());
    return 0;
}
