// intrinsym_openmesh INPUT OUTPUT.ply — detect symmetries of a mesh read by OpenMesh and write a
// binary PLY with vertex colours, a float "quality" property (symmetry confidence) and an int
// "intrinsym_image" property (image vertex under the first reported symmetry, -1 outside it).
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <iostream>

#include "intrinsym_openmesh.hpp"

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;

int main(int argc, char **argv) {
    if (argc != 3) {
        std::cerr << "usage: intrinsym_openmesh INPUT OUTPUT.ply\n";
        return 2;
    }
    Mesh mesh;
    if (!OpenMesh::IO::read_mesh(mesh, argv[1])) {
        std::cerr << "cannot read " << argv[1] << "\n";
        return 2;
    }
    auto d = intrinsym::detect(mesh);
    if (!d.ok()) {
        std::cerr << "intrinsym: " << d.error << "\n";
        return 1;
    }
    std::cout << argv[1] << ": " << d.count() << " symmetries\n";
    OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexColor | OpenMesh::IO::Options::Custom | OpenMesh::IO::Options::Binary;
    if (!OpenMesh::IO::write_mesh(mesh, argv[2], opt)) {
        std::cerr << "cannot write " << argv[2] << "\n";
        return 1;
    }
    return 0;
}
