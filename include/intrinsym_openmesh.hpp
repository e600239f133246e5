// intrinsym_openmesh.hpp — header-only adapter between OpenMesh triangle meshes and the
// intrinsym C API (Debian's libopenmesh-dev 9.0; link OpenMeshCore and intrinsym).
//
//   intrinsym::OpenMeshDetection d = intrinsym::detect(mesh);        // default parameters
//   if (!d.ok()) std::cerr << d.error << "\n";
//   // per vertex: property "intrinsym_image" (int, image under the first reported symmetry or -1),
//   // property "quality" (float, symmetry confidence), vertex colours (a vertex and its image
//   // share a colour); d.result stays valid (and owned) until d is destroyed.
//
// Deleted vertices and faces are skipped; a face that is not a triangle is refused with a
// clear error (triangulate first). Vertex indices passed to the library are the compacted
// indices of the non-deleted vertices; the properties are written on the mesh's own handles.
#ifndef INTRINSYM_OPENMESH_HPP
#define INTRINSYM_OPENMESH_HPP

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "intrinsym.h"

namespace intrinsym {

/// A detection on an OpenMesh mesh. Owns the C result (freed in the destructor).
struct OpenMeshDetection {
    sym_status status = SYM_STATUS_PANIC;
    std::string error;               ///< empty on success
    sym_result *result = nullptr;    ///< NULL on failure
    std::vector<int> to_mesh;        ///< compacted index -> mesh vertex index

    bool ok() const { return status == SYM_STATUS_OK; }
    std::size_t count() const { return sym_count(result); }
    OpenMeshDetection() = default;
    OpenMeshDetection(const OpenMeshDetection &) = delete;
    OpenMeshDetection &operator=(const OpenMeshDetection &) = delete;
    OpenMeshDetection(OpenMeshDetection &&o) noexcept
        : status(o.status), error(std::move(o.error)), result(o.result), to_mesh(std::move(o.to_mesh)) { o.result = nullptr; }
    ~OpenMeshDetection() { sym_free(result); }
};

namespace detail {
inline std::string last_error() {
    std::size_t len = 0;
    sym_last_error(nullptr, 0, &len);
    std::string s(len + 1, '\0');
    sym_last_error(&s[0], s.size(), nullptr);
    s.resize(len);
    return s;
}
}  // namespace detail

/// Runs sym_detect on `mesh` and, on success, writes the "intrinsym_image" and "quality"
/// vertex properties (persistent, so OpenMesh writes them to PLY as custom properties) and
/// vertex colours from the first reported symmetry. `params` may be NULL (defaults).
template <class Mesh>
OpenMeshDetection detect(Mesh &mesh, const sym_params *params = nullptr, sym_progress_fn progress = nullptr, void *user_data = nullptr) {
    OpenMeshDetection d;
    std::vector<int> to_compact(mesh.n_vertices(), -1);
    std::vector<double> vertices;
    std::vector<std::uint32_t> triangles;
    for (auto vh : mesh.vertices()) {
        if (mesh.has_vertex_status() && mesh.status(vh).deleted()) continue;
        to_compact[vh.idx()] = static_cast<int>(d.to_mesh.size());
        d.to_mesh.push_back(vh.idx());
        const auto p = mesh.point(vh);
        vertices.insert(vertices.end(), {double(p[0]), double(p[1]), double(p[2])});
    }
    for (auto fh : mesh.faces()) {
        if (mesh.has_face_status() && mesh.status(fh).deleted()) continue;
        std::size_t k = 0;
        for (auto vh : mesh.fv_range(fh)) {
            if (to_compact[vh.idx()] < 0) {
                d.status = SYM_STATUS_INVALID_MESH;
                d.error = "face " + std::to_string(fh.idx()) + " uses a deleted vertex";
                return d;
            }
            triangles.push_back(static_cast<std::uint32_t>(to_compact[vh.idx()]));
            ++k;
        }
        if (k != 3) {
            d.status = SYM_STATUS_INVALID_MESH;
            d.error = "face " + std::to_string(fh.idx()) + " has " + std::to_string(k) + " vertices; intrinsym needs triangles (triangulate first)";
            return d;
        }
    }
    if (vertices.empty() || triangles.empty()) {
        d.status = SYM_STATUS_INVALID_MESH;
        d.error = "mesh has no (non-deleted) vertices or faces";
        return d;
    }
    d.status = sym_detect(vertices.data(), vertices.size() / 3, triangles.data(), triangles.size() / 3,
                          params, progress, user_data, &d.result);
    if (d.status != SYM_STATUS_OK) {
        d.error = std::string(sym_status_str(d.status)) + ": " + detail::last_error();
        d.result = nullptr;
        return d;
    }
    OpenMesh::VPropHandleT<int> image;
    OpenMesh::VPropHandleT<float> quality;
    if (!mesh.get_property_handle(image, "intrinsym_image")) mesh.add_property(image, "intrinsym_image");
    if (!mesh.get_property_handle(quality, "quality")) mesh.add_property(quality, "quality");
    mesh.property(image).set_persistent(true);
    mesh.property(quality).set_persistent(true);
    mesh.request_vertex_colors();
    const double *summary = sym_vertex_symmetry(d.result);
    sym_symmetry s{};
    s.struct_size = sizeof s;
    const bool have = sym_count(d.result) > 0 && sym_get_map(d.result, 0, &s) == SYM_STATUS_OK;
    // Bounding box for the correspondence colouring (midpoint of v and its image).
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (std::size_t i = 0; i < d.to_mesh.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            lo[c] = std::fmin(lo[c], vertices[3 * i + c]);
            hi[c] = std::fmax(hi[c], vertices[3 * i + c]);
        }
    for (std::size_t i = 0; i < d.to_mesh.size(); ++i) {
        auto vh = mesh.vertex_handle(static_cast<unsigned>(d.to_mesh[i]));
        const std::int64_t t = have ? s.map[i] : -1;
        mesh.property(image, vh) = t < 0 ? -1 : d.to_mesh[static_cast<std::size_t>(t)];
        mesh.property(quality, vh) = static_cast<float>(summary[i]);
        typename Mesh::Color col(150, 150, 150);
        if (t >= 0) {
            for (int c = 0; c < 3; ++c) {
                const double mid = 0.5 * (vertices[3 * i + c] + vertices[3 * std::size_t(t) + c]);
                const double x = hi[c] > lo[c] ? (mid - lo[c]) / (hi[c] - lo[c]) : 0.5;
                col[c] = static_cast<unsigned char>(40.0 + 200.0 * x);
            }
        }
        mesh.set_color(vh, col);
    }
    return d;
}

}  // namespace intrinsym

#endif  // INTRINSYM_OPENMESH_HPP
