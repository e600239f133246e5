// The OpenMesh adapter end to end: run examples' intrinsym_openmesh logic on the rest-pose
// quadruped, write the PLY, read it back with OpenMesh and check colours, quality and that the
// written image property sends vertices to their mirror images. Usage: test_openmesh IN.off OUT.ply
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "intrinsym_openmesh.hpp"

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

#define CHECK(c, msg) do { if (!(c)) { std::fprintf(stderr, "FAIL: %s\n", msg); return 1; } } while (0)

int main(int argc, char **argv) {
    CHECK(argc == 3, "usage");
    Mesh mesh;
    CHECK(OpenMesh::IO::read_mesh(mesh, argv[1]), "read input");
    {
        // A quad is refused with a clear error.
        OpenMesh::PolyMesh_ArrayKernelT<> poly;
        auto a = poly.add_vertex({0, 0, 0}), b = poly.add_vertex({1, 0, 0}), c = poly.add_vertex({1, 1, 0}), e = poly.add_vertex({0, 1, 0});
        poly.add_face(a, b, c, e);
        auto bad = intrinsym::detect(poly);
        CHECK(!bad.ok() && bad.error.find("triangles") != std::string::npos, "quad refused");
    }
    auto d = intrinsym::detect(mesh);
    CHECK(d.ok(), d.error.c_str());
    OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexColor | OpenMesh::IO::Options::Custom | OpenMesh::IO::Options::Binary;
    CHECK(OpenMesh::IO::write_mesh(mesh, argv[2], opt), "write PLY");

    Mesh back;
    OpenMesh::VPropHandleT<float> quality;
    OpenMesh::VPropHandleT<int> image;
    back.add_property(quality, "quality");
    back.add_property(image, "intrinsym_image");
    back.property(quality).set_persistent(true);
    back.property(image).set_persistent(true);
    back.request_vertex_colors();
    OpenMesh::IO::Options ropt = OpenMesh::IO::Options::VertexColor | OpenMesh::IO::Options::Custom;
    CHECK(OpenMesh::IO::read_mesh(back, argv[2], ropt), "read PLY back");
    CHECK(ropt.check(OpenMesh::IO::Options::VertexColor), "PLY has vertex colours");
    CHECK(back.n_vertices() == mesh.n_vertices(), "vertex count");
    std::size_t exact = 0, same_colour = 0, n = back.n_vertices();
    for (auto vh : back.vertices()) {
        const float q = back.property(quality, vh);
        CHECK(q >= 0.0f && q <= 1.0f, "quality in [0, 1]");
        const int t = back.property(image, vh);
        CHECK(t >= -1 && t < int(n), "image in range");
        if (t < 0) continue;
        const auto p = back.point(vh), m = back.point(back.vertex_handle(unsigned(t)));
        if (std::fabs(p[0] + m[0]) < 1e-5 && std::fabs(p[1] - m[1]) < 1e-5 && std::fabs(p[2] - m[2]) < 1e-5) ++exact;
        if (back.color(vh) == back.color(back.vertex_handle(unsigned(t)))) ++same_colour;
    }
    std::printf("test_openmesh: %zu of %zu vertices map to their mirror image, %zu share its colour\n", exact, n, same_colour);
    CHECK(exact >= n * 95 / 100, "mirror images");
    CHECK(same_colour >= n * 95 / 100, "correspondence colours");
    return 0;
}
