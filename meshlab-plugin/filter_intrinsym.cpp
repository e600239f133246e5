#include "filter_intrinsym.h"

#include <vector>

#include "intrinsym.h"

namespace {

enum Show { SHOW_STRONGEST = 0, SHOW_ALL = 1, SHOW_INDEX = 2 };
enum Colouring { COLOUR_CORRESPONDENCE = 0, COLOUR_GROUPS = 1, COLOUR_QUALITY = 2 };

const unsigned char PALETTE[10][3] = {{78, 121, 167}, {242, 142, 43}, {225, 87, 89}, {118, 183, 178}, {89, 161, 79},
                                      {237, 201, 72}, {176, 122, 161}, {255, 157, 167}, {156, 117, 95}, {186, 176, 172}};

// MeshLab's progress bar as the library's progress callback. CallBackPos returning false
// (a cancelled run) cancels the detection.
struct Progress {
    vcg::CallBackPos *cb;
};
int progress(float fraction, void *user_data) {
    const Progress *p = static_cast<const Progress *>(user_data);
    if (p == nullptr || p->cb == nullptr) return 1;
    return p->cb(int(100.0f * fraction), "Intrinsic symmetry") ? 1 : 0;
}

QString last_error() {
    char buf[1024];
    sym_last_error(buf, sizeof buf, nullptr);
    return QString::fromUtf8(buf);
}

// FNV-1a over bytes: the fingerprint of a detection's input.
void fnv(unsigned long long &h, const void *data, size_t n) {
    const unsigned char *b = static_cast<const unsigned char *>(data);
    for (size_t i = 0; i < n; ++i) {
        h ^= b[i];
        h *= 1099511628211ULL;
    }
}

// An integer parameter checked against its range, with a message that names it.
bool in_range(int value, int lo, int hi, const char *name, QString &message) {
    if (value >= lo && value <= hi) return true;
    message = QString("%1: %2 is out of range (%3 to %4).").arg(name).arg(value).arg(lo).arg(hi);
    return false;
}

}  // namespace

FilterIntrinsymPlugin::FilterIntrinsymPlugin()
{
    typeList << FP_INTRINSIC_SYMMETRY << FP_INTRINSIC_SYMMETRY_PARTS;
    for (FilterIDType tt : types()) actionList << new QAction(filterName(tt), this);
}

FilterIntrinsymPlugin::~FilterIntrinsymPlugin() { sym_free(cached); }

QString FilterIntrinsymPlugin::pluginName() const { return "FilterIntrinsym"; }

QString FilterIntrinsymPlugin::filterName(FilterIDType filter) const
{
    return filter == FP_INTRINSIC_SYMMETRY_PARTS ? "Intrinsic Symmetry: Detect with Repeated Parts" : "Intrinsic Symmetry: Detect";
}

QString FilterIntrinsymPlugin::filterInfo(FilterIDType filter) const
{
    const QString parts = filter == FP_INTRINSIC_SYMMETRY_PARTS
                              ? "<p><b>With repeated parts</b> (experimental): also looks for partial symmetries between "
                                "repeated parts that no symmetry of the whole shape relates (a front paw and a hind paw, "
                                "identical fingers or spikes), each in a basis of its own parts; they are logged after the "
                                "global symmetries as <i>partial</i>, with their region size; show one with Show = Index. "
                                "Slower (up to about a third more time).</p>"
                              : "";
    return "Detects the intrinsic symmetries of the mesh (Mukhopadhyay, Bhandarkar & Porikli, "
           "<i>Detection and Characterization of Intrinsic Symmetry</i>): self-maps that preserve "
           "distances on the surface, including ones a pose hides from a mirror plane and partial "
           "ones. Writes per-vertex <b>quality</b> = symmetry confidence in [0, 1] and per-vertex "
           "<b>colour</b>: with <i>Correspondence</i>, a vertex and its image share a colour; with "
           "<i>Groups</i>, each symmetry's region is painted with its group colour; with "
           "<i>Quality</i>, a red-to-blue ramp of the confidence. One line per symmetry is logged "
           "(kind, orientation, score, group, order, complexity, region size), strongest (highest "
           "score) first, a partial symmetry's score counting a third against global ones. "
           "Library: intrinsym "
           + QString(sym_version()) + "." + parts;
}

FilterIntrinsymPlugin::FilterClass FilterIntrinsymPlugin::getClass(QAction *)
{
    return FilterClass(MeshFilterInterface::Quality | MeshFilterInterface::VertexColoring);
}

MeshFilterInterface::FILTER_ARITY FilterIntrinsymPlugin::filterArity(QAction *) const { return SINGLE_MESH; }

int FilterIntrinsymPlugin::getPreConditions(QAction *) const { return MeshModel::MM_NONE; }

int FilterIntrinsymPlugin::postCondition(QAction *) const { return MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR; }

void FilterIntrinsymPlugin::initParameterSet(QAction *, MeshModel &, RichParameterList &parlst)
{
    parlst.addParam(RichInt("eigenpairs", 100, "Eigenpairs", "Number of Laplace-Beltrami eigenpairs (3 to 1000)."));
    parlst.addParam(RichInt("samples", 64, "Samples", "Farthest-point samples used for voting (8 to 1000; the paper uses 20-100)."));
    parlst.addParam(RichFloat("wksQuantile", 0.2f, "WKS quantile", "Good voters: sample pairs whose wave kernel signatures are closer than this quantile of all pairs."));
    parlst.addParam(RichFloat("votingEps", 0.04f, "Voting tolerance", "Distance tolerance of the voting, as a fraction of the biharmonic diameter."));
    parlst.addParam(RichFloat("accept", 0.03f, "Region tolerance", "A vertex belongs to a symmetry's region when its distances are preserved within this fraction of the diameter."));
    parlst.addParam(RichInt("seed", 0, "Seed", "Random seed: results are deterministic for a seed."));
    parlst.addParam(RichInt("proxyVertices", 6000, "Proxy vertices", "Meshes of more than 1.5 times this many vertices get their maps on a proxy of this many vertices, lifted to every vertex (much faster; 0 = always the whole mesh; else 1000 to 1000000)."));
    parlst.addParam(RichEnum("show", SHOW_STRONGEST, QStringList() << "Strongest" << "All" << "Index", "Show", "Which symmetry to write: the strongest (the first logged), all (quality = best confidence over all), or the one at Index."));
    parlst.addParam(RichInt("index", 0, "Index", "Symmetry shown when Show is Index, in the logged order (0 = the first)."));
    parlst.addParam(RichEnum("colouring", COLOUR_CORRESPONDENCE, QStringList() << "Correspondence" << "Groups" << "Quality", "Colouring", "Correspondence: a vertex and its image share a colour. Groups: regions painted by symmetry group. Quality: colour ramp of the confidence."));
}

bool FilterIntrinsymPlugin::applyFilter(QAction *action, MeshDocument &md, const RichParameterList &par, vcg::CallBackPos *cb)
{
    // A failure is reported twice: errorMessage (the GUI's dialog) and the log (meshlabserver
    // prints the log but not errorMessage).
    auto fail = [this](const QString &message) {
        errorMessage = message;
        Log("Intrinsic Symmetry: %s", qUtf8Printable(message));
        return false;
    };
    MeshModel *mm = md.mm();
    if (mm == nullptr) return fail("No mesh.");
    CMeshO &m = mm->cm;
    // Pack the non-deleted vertices and faces; `compact` maps MeshLab's vertex index to ours.
    std::vector<int> compact(m.vert.size(), -1);
    std::vector<CMeshO::VertexPointer> verts;
    std::vector<double> xyz;
    for (size_t i = 0; i < m.vert.size(); ++i) {
        if (m.vert[i].IsD()) continue;
        compact[i] = int(verts.size());
        verts.push_back(&m.vert[i]);
        const auto &p = m.vert[i].cP();
        xyz.push_back(p[0]);
        xyz.push_back(p[1]);
        xyz.push_back(p[2]);
    }
    std::vector<uint32_t> tri;
    for (auto fi = m.face.begin(); fi != m.face.end(); ++fi) {
        if (fi->IsD()) continue;
        for (int k = 0; k < 3; ++k) tri.push_back(uint32_t(compact[vcg::tri::Index(m, fi->V(k))]));
    }
    if (tri.empty()) return fail("needs a triangle mesh: this mesh has no faces (a point cloud?).");

    // Every parameter is checked here, with its name and range in the message (MeshLab's
    // dialog takes any integer and any enum index a script gives).
    QString bad;
    const int eigenpairs = par.getInt("eigenpairs"), samples = par.getInt("samples"), seed = par.getInt("seed"), proxy = par.getInt("proxyVertices");
    const int show = par.getEnum("show"), index = par.getInt("index"), colouring = par.getEnum("colouring");
    if (!in_range(eigenpairs, 3, 1000, "Eigenpairs", bad) || !in_range(samples, 8, 1000, "Samples", bad) ||
        !in_range(seed, 0, 2147483647, "Seed", bad) || !in_range(proxy, 0, 1000000, "Proxy vertices", bad) ||
        !in_range(show, SHOW_STRONGEST, SHOW_INDEX, "Show (0 Strongest, 1 All, 2 Index)", bad) ||
        !in_range(colouring, COLOUR_CORRESPONDENCE, COLOUR_QUALITY, "Colouring (0 Correspondence, 1 Groups, 2 Quality)", bad) ||
        (show == SHOW_INDEX && !in_range(index, 0, 2147483647, "Index", bad)))
        return fail(bad);
    sym_params *params = sym_params_new();
    if (params == nullptr) return fail("out of memory.");
    // The setters check the rest (the float ranges, proxy vertices 1 to 999) and say which.
    sym_status st = sym_params_set_eigenpairs(params, size_t(eigenpairs));
    if (st == SYM_STATUS_OK) st = sym_params_set_samples(params, size_t(samples));
    if (st == SYM_STATUS_OK) st = sym_params_set_wks_quantile(params, par.getFloat("wksQuantile"));
    if (st == SYM_STATUS_OK) st = sym_params_set_voting_eps(params, par.getFloat("votingEps"));
    if (st == SYM_STATUS_OK) st = sym_params_set_accept(params, par.getFloat("accept"));
    if (st == SYM_STATUS_OK) st = sym_params_set_seed(params, uint64_t(seed));
    if (st == SYM_STATUS_OK) st = sym_params_set_proxy_vertices(params, size_t(proxy));
    const int parts = ID(action) == FP_INTRINSIC_SYMMETRY_PARTS ? 1 : 0;
    if (st == SYM_STATUS_OK) st = sym_params_set_parts(params, parts);
    // Non-manifold edges are accepted and coincident vertices welded (the library's defaults).
    // There is deliberately no parameter for either: MeshLab 2020.09's meshlabserver aborts
    // (an assertion) on a script that does not list every parameter of a filter, so a new
    // parameter would crash every saved script (README, "Using intrinsym in MeshLab", pitfalls).
    if (st != SYM_STATUS_OK) {
        sym_params_free(params);
        return fail(QString("invalid parameter: ") + last_error());
    }
    // The fingerprint of this detection's input: the packed mesh and every detection
    // parameter (not Show, Index or Colouring, which only choose what is painted).
    unsigned long long key = 14695981039346656037ULL;
    fnv(key, xyz.data(), xyz.size() * sizeof(double));
    fnv(key, tri.data(), tri.size() * sizeof(uint32_t));
    const float floats[3] = {par.getFloat("wksQuantile"), par.getFloat("votingEps"), par.getFloat("accept")};
    const int ints[5] = {eigenpairs, samples, seed, proxy, parts};
    fnv(key, floats, sizeof floats);
    fnv(key, ints, sizeof ints);
    sym_result *result = nullptr;
    if (cached != nullptr && cachedKey == key) {
        result = cached;
        Log("Intrinsic Symmetry: reusing the last detection (same mesh and detection parameters).");
        sym_params_free(params);
    } else {
        Progress state{cb};
        st = sym_detect(xyz.data(), verts.size(), tri.data(), tri.size() / 3, params, progress, &state, &result);
        sym_params_free(params);
        if (st != SYM_STATUS_OK) return fail(QString("failed (") + sym_status_str(st) + "): " + last_error());
        sym_free(cached);
        cached = result;
        cachedKey = key;
    }
    {
        // What validation found and decided, so that nothing is dropped silently.
        sym_mesh_report info{};
        info.struct_size = sizeof info;
        if (sym_get_mesh_report(result, &info) == SYM_STATUS_OK) {
            Log("Mesh: %d vertices, %d triangles; %d coincident vertices welded (%d triangles collapsed); %d repeated triangles dropped; "
                "%d unreferenced vertices ignored; %d components, %d processed each on its own, %d vertices of smaller ones ignored (left grey, quality 0); "
                "%d non-manifold edges; %d zero-area triangles; %d holes capped for the detection (an image in a hole is shown on its rim)",
                int(info.input_vertices), int(info.input_triangles), int(info.welded_vertices), int(info.collapsed_triangles),
                int(info.duplicate_triangles), int(info.isolated_vertices), int(info.components), int(info.kept_components),
                int(info.ignored_component_vertices), int(info.non_manifold_edges), int(info.degenerate_triangles), int(info.closed_holes));
        }
        const int dimension = sym_continuous_dimension(result);
        if (dimension > 0)
            Log("A continuous symmetry: a %d-parameter family of isometries; one map of each orientation type is listed.", dimension);
    }

    const size_t count = sym_count(result);
    std::vector<sym_symmetry> syms(count);
    for (size_t i = 0; i < count; ++i) {
        syms[i] = sym_symmetry{};
        syms[i].struct_size = sizeof(sym_symmetry);
        sym_get_map(result, i, &syms[i]);
        Log("Symmetry #%d: %s, orientation-%s, score %.3f, group %u, order %u, complexity %.3f, region %d of %d vertices, component %u -> %u",
            int(i), syms[i].kind == SYM_KIND_GLOBAL ? "global" : "partial",
            syms[i].reversal > 0.5 ? "reversing" : "preserving", syms[i].score, syms[i].group, syms[i].order,
            syms[i].complexity, int(syms[i].region_size), int(verts.size()), syms[i].source_component, syms[i].target_component);
    }
    if (count == 0) Log("No intrinsic symmetry found.");

    if (show == SHOW_INDEX && size_t(index) >= count)
        return fail(QString("Index: %1 is out of range: %2 symmetries were found (0 to %3).").arg(index).arg(count).arg(int(count) - 1));
    const sym_symmetry *chosen = count == 0 ? nullptr : &syms[show == SHOW_INDEX ? size_t(index) : 0];
    const double *summary = sym_vertex_symmetry(result);

    mm->updateDataMask(MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR);
    // Correspondence colours come from the library (one implementation for the CLI's PLY and
    // this filter): a vertex and its image alike, also where their midpoint is the same
    // everywhere (a sphere's antipodal map).
    std::vector<unsigned char> rgb;
    if (colouring == COLOUR_CORRESPONDENCE && chosen) {
        rgb.resize(3 * verts.size());
        if (sym_correspondence_colours(xyz.data(), verts.size(), chosen->map, rgb.data()) != SYM_STATUS_OK) rgb.clear();
    }
    for (size_t i = 0; i < verts.size(); ++i) {
        const double q = show == SHOW_ALL ? summary[i] : (chosen ? chosen->confidence[i] : 0.0);
        verts[i]->Q() = CMeshO::ScalarType(q);
        vcg::Color4b c(150, 150, 150, 255);
        if (!rgb.empty()) {
            c = vcg::Color4b(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 255);
        } else if (colouring == COLOUR_GROUPS) {
            for (size_t s = 0; s < count; ++s) {
                if (show != SHOW_ALL && &syms[s] != chosen) continue;
                if (syms[s].map[i] >= 0) {
                    const unsigned char *g = PALETTE[syms[s].group % 10];
                    c = vcg::Color4b(g[0], g[1], g[2], 255);
                    break;
                }
            }
        }
        verts[i]->C() = c;
    }
    if (colouring == COLOUR_QUALITY) vcg::tri::UpdateColor<CMeshO>::PerVertexQualityRamp(m, 0.0f, 1.0f);
    return true;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterIntrinsymPlugin)
