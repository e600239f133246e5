//! Maps between congruent components (beyond the paper; issue 16, item 4): a pair of shoes,
//! two copies of a part, the halves of a model cut apart.
//!
//! The paper's pipeline works on one connected surface: its eigenbasis, biharmonic distances
//! and voting cannot relate two components (no distance joins them, and the spectrum of a
//! disconnected surface mixes the components' spectra). Each component is therefore detected
//! on its own (`crate::detect`), and a map *between* two components is a shape-matching
//! problem between two surfaces with their own bases.
//!
//! **Congruence test.** Isometric surfaces have the same area and the same Laplace–Beltrami
//! spectrum. Two components are candidates when their areas agree within `tolerance` and the
//! first `eigenvalues` non-zero eigenvalues of their unit-area copies agree within `tolerance`
//! on average (relative): cheap, and it rules out most pairs before any map is made. Equal
//! spectra do not prove isometry; the map's distortion (below) decides.
//!
//! **The map.** The functional-map energy of [`super::orientation`] written between two shapes
//! ([`super::orientation::fmap_between`]): descriptor preservation, commutativity with the
//! Laplacian and with the descriptors' multiplication operators, and orientation — reversing
//! for a mirror image (a left and a right shoe), preserving for a copy. Both types are solved
//! (exact least squares, as for the self-map hypothesis), each turned into a point map
//! ([`super::spectral_init::point_map_between`]) and refined by ZoomOut between the two bases
//! ([`super::zoomout::zoomout_between`]). The map back is refined from the transposed
//! functional map (an isometry's functional map is orthogonal). The orientation term is what
//! makes the answer unique for a component that is itself mirror-symmetric (a human): its copy
//! and its mirror image are then two different maps, and each type has one.
//!
//! **Judging.** The mean change of biharmonic distances between farthest-point samples of the
//! source and their images, over the source's biharmonic diameter — the distortion the rest of
//! the pipeline uses ([`crate::characterize::distortion`]), here across two embeddings (both of
//! unit-area copies, so their distances are comparable; [`crate::characterize::distortion_between`])
//! — the worse of the two directions. The
//! type with the lower distortion is kept, if it is below the pipeline's `max_distortion`.

use faer::Mat;

use super::orientation::{self, Operators};
use super::zoomout::ZoomBasis;
use super::MapParams;
use crate::distance::BiharmonicEmbedding;
use crate::mesh::Mesh;
use crate::sampling::farthest_point;
use crate::spectral::Eigenbasis;

/// Parameters of the congruence test.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct CongruentParams {
    /// Relative tolerance on areas and eigenvalues (default 0.05; discretisations of one surface
    /// at different resolutions differ by about 1% in their first eigenvalues).
    pub tolerance: f64,
    /// Eigenvalues compared (default 20).
    pub eigenvalues: usize,
    /// Farthest-point samples whose distances judge a map (default 64, as voting's).
    pub samples: usize,
}

impl Default for CongruentParams {
    fn default() -> Self {
        CongruentParams { tolerance: 0.05, eigenvalues: 20, samples: 64 }
    }
}

/// One component as the congruence stage sees it: its unit-area copy, the eigenbasis,
/// descriptors and biharmonic embedding computed on that copy, and its area in the units of
/// the whole mesh.
pub struct Part<'a> {
    /// The component, scaled to unit area.
    pub mesh: &'a Mesh,
    /// Its eigenbasis.
    pub basis: &'a Eigenbasis,
    /// Its WKS descriptors.
    pub desc: &'a Mat<f64>,
    /// Its biharmonic embedding.
    pub emb: &'a BiharmonicEmbedding,
    /// Its area before scaling (any common unit).
    pub area: f64,
}

/// Whether `a` and `b` can be congruent: same area and spectrum within the tolerance.
pub fn congruent(a: &Part<'_>, b: &Part<'_>, params: &CongruentParams) -> bool {
    let tol = params.tolerance;
    if !(a.area > 0.0 && b.area > 0.0) || (a.area / b.area - 1.0).abs() > tol {
        return false;
    }
    let m = params.eigenvalues.min(a.basis.k()).min(b.basis.k());
    if m < 2 {
        return false;
    }
    let mean = (1..m).map(|i| (a.basis.evals[i] / b.basis.evals[i].max(f64::MIN_POSITIVE) - 1.0).abs()).sum::<f64>() / (m - 1) as f64;
    mean <= tol
}

/// A map between two congruent components, in their own vertex indices.
#[derive(Clone, Debug)]
pub struct Between {
    /// `(n_a,)` image in `b` of every vertex of `a`.
    pub forward: Vec<usize>,
    /// `(n_b,)` image in `a` of every vertex of `b`.
    pub backward: Vec<usize>,
    /// The worse of the two directions' distortions (fraction of the diameter).
    pub distortion: f64,
    /// Whether the map reverses orientation (a mirror image).
    pub reverses: bool,
}

/// What a side of the matching needs, built once for both orientation types.
struct Side<'a> {
    part: &'a Part<'a>,
    ops: Operators,
    adjacency: (Vec<usize>, Vec<u32>),
    zoom: ZoomBasis,
    /// Evenly strided vertices for the coarse search of the point map.
    search: Vec<usize>,
    samples: Vec<usize>,
    diameter: f64,
}

impl<'a> Side<'a> {
    fn new(part: &'a Part<'a>, maps: &MapParams, params: &CongruentParams) -> Option<Side<'a>> {
        let mesh = part.mesh;
        let ops = orientation::operators(mesh, &mesh.oriented_triangles(), part.basis, part.desc, &maps.orientation)?;
        let samples = farthest_point(part.emb, params.samples, 0).vertices;
        let diameter = part.emb.diameter_of(&samples);
        Some(Side {
            part,
            ops,
            adjacency: mesh.adjacency(),
            zoom: ZoomBasis::new(part.basis, maps.zoomout_k.max(1)),
            search: super::search_subset(mesh.num_vertices(), maps),
            samples,
            diameter,
        })
    }

    /// The point map to `dst` of the functional map `c` (`Φ_dst(T v) ≈ Φ_src(v) C`), refined.
    fn map_to(&self, dst: &Side<'_>, c: &Mat<f64>, maps: &MapParams) -> Vec<usize> {
        let mut map = super::spectral_init::point_map_between(self.part.basis, &self.adjacency, dst.part.basis, &dst.adjacency, c, &dst.search, super::spectral_init::Conversion::Adjoint);
        if maps.zoomout_k > c.nrows() {
            super::zoomout::zoomout_between(&self.zoom, &self.adjacency, &dst.zoom, &dst.adjacency, &mut map, c.nrows(), maps.zoomout_k, maps.zoomout_step, super::zoomout::Involution::Off);
        }
        map
    }

    /// Mean `|d_src(x, y) − d_dst(T x, T y)|` over the samples' pairs, over the diameter.
    fn distortion(&self, dst: &Side<'_>, map: &[usize]) -> f64 {
        if self.samples.len() < 2 || self.diameter.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return f64::INFINITY;
        }
        let anchors: Vec<(usize, usize)> = self.samples.iter().map(|&x| (x, map[x])).collect();
        crate::characterize::distortion_between(&anchors, self.part.emb, dst.part.emb, self.diameter)
    }
}

/// The map between congruent components `a` and `b` of lower distortion among the
/// orientation-reversing and the orientation-preserving one, if it distorts by at most
/// `max_distortion`; `None` otherwise or when the operators cannot be built.
pub fn map_between(a: &Part<'_>, b: &Part<'_>, maps: &MapParams, params: &CongruentParams, max_distortion: f64) -> Option<Between> {
    let (sa, sb) = crate::parallel::join(|| Side::new(a, maps, params), || Side::new(b, maps, params));
    let (sa, sb) = (sa?, sb?);
    let attempt = |reverses: bool| -> Option<Between> {
        let c = orientation::fmap_between(&sa.ops, &sb.ops, reverses, &maps.orientation)?;
        let back = c.transpose().to_owned();
        let (forward, backward) = crate::parallel::join(|| sa.map_to(&sb, &c, maps), || sb.map_to(&sa, &back, maps));
        let distortion = sa.distortion(&sb, &forward).max(sb.distortion(&sa, &backward));
        Some(Between { forward, backward, distortion, reverses })
    };
    [true, false]
        .into_iter()
        .filter_map(attempt)
        .min_by(|x, y| x.distortion.total_cmp(&y.distortion))
        .filter(|m| m.distortion <= max_distortion)
}
