//! Laplace–Beltrami eigenbasis: the foundation every later stage reads.
//!
//! The generalized eigenproblem
//! $$L\,\varphi_i = \lambda_i M \varphi_i,\qquad 0 = \lambda_0 < \lambda_1 \le \dots \le \lambda_{k-1},\qquad \Phi^\top M \Phi = I$$
//! with `L` the cotangent Laplacian ([`cotan`], PSD convention) and `M` the lumped mass
//! ([`mass`]; on the coarse mesh of a large one, the area of each vertex's cell on the fine
//! mesh: [`crate::hierarchy`]), solved by shift-invert block Lanczos ([`eigen`]). The paper
//! (Mukhopadhyay, Bhandarkar & Porikli, "Detection and Characterization of Intrinsic Symmetry",
//! §3) builds both its descriptor (WKS) and its intrinsic distance (biharmonic) on this basis.
//!
//! [`Eigenbasis::compute`] is the one-shot entry; the result is shared read-only.

pub mod cotan;
pub mod eigen;
pub mod factor;
pub(crate) mod kernels;
pub mod mass;

pub use eigen::{EigenInfo, EigenParams, Solver};

use std::fmt;
use std::time::Instant;

use faer::Mat;
use sprs::CsMat;

use crate::mesh::Mesh;

/// Why the eigenbasis could not be computed.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum SpectralError {
    /// More eigenpairs asked for than the mesh has vertices (or zero).
    TooManyEigenpairs {
        /// Requested.
        k: usize,
        /// Vertices.
        n: usize,
    },
    /// The sparse Cholesky factorization or a dense decomposition failed.
    Factorization(String),
    /// Lanczos did not converge within the restart budget.
    NotConverged {
        /// Pairs converged (including the constant one).
        converged: usize,
        /// Pairs wanted.
        wanted: usize,
    },
    /// The progress callback asked to stop.
    Cancelled,
}

impl fmt::Display for SpectralError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SpectralError::TooManyEigenpairs { k, n } => {
                write!(f, "{k} eigenpairs requested, but the mesh allows 1 to {n} (its vertex count)")
            }
            SpectralError::Factorization(m) => write!(f, "factorization failed: {m}"),
            SpectralError::NotConverged { converged, wanted } => {
                // Name what a user can change: k is a parameter of every front end, the restart
                // budget only of `EigenParams`.
                write!(
                    f,
                    "Lanczos converged {converged} of {wanted} eigenpairs: the mesh's Laplacian is badly \
                     conditioned (nearly degenerate triangles: a surface flattened onto a line or stretched \
                     thousands of times along one axis); repair the mesh, or ask for fewer eigenpairs \
                     (k: CLI -k, C sym_params_set_eigenpairs)"
                )
            }
            SpectralError::Cancelled => write!(f, "cancelled"),
        }
    }
}

impl std::error::Error for SpectralError {}

/// The `k` lowest Laplace–Beltrami eigenpairs of a mesh, with the operators they came from.
#[derive(Clone, Debug)]
pub struct Eigenbasis {
    /// `(k,)` eigenvalues, ascending, `evals[0] = 0`.
    pub evals: Vec<f64>,
    /// `(n, k)` eigenvectors, M-orthonormal; column 0 is the constant `1/√area`.
    pub evecs: Mat<f64>,
    /// `(n,)` lumped mass (on a coarse mesh of the hierarchy, its cells' areas).
    pub mass: Vec<f64>,
    /// `(n, n)` cotangent Laplacian.
    pub laplacian: CsMat<f64>,
    /// Surface area (`Σ mass`).
    pub area: f64,
    /// Solver statistics.
    pub info: EigenInfo,
    /// Seconds spent assembling `L` and `M`.
    pub assembly_seconds: f64,
}

impl Eigenbasis {
    /// Assembles `L` and `M` and solves for `params.k` eigenpairs.
    pub fn compute(mesh: &Mesh, params: &EigenParams) -> Result<Eigenbasis, SpectralError> {
        Self::compute_with_progress(mesh, params, &mut |_| true)
    }

    /// As [`Eigenbasis::compute`], reporting progress in [0, 1]; `progress` returning `false` cancels.
    pub fn compute_with_progress(
        mesh: &Mesh,
        params: &EigenParams,
        progress: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Eigenbasis, SpectralError> {
        Self::compute_with_mass(mesh, None, None, params, progress)
    }

    /// As [`Eigenbasis::compute_with_progress`], with the vertex masses `mass` (in the mesh's
    /// units, `(n,)`, positive) in place of the lumped mass when given: a coarse mesh's cells
    /// measured on its fine mesh ([`crate::hierarchy::Hierarchy::cell_mass`]); and with the
    /// edges' lengths of the stiffness stretched by `stretch` when given (one factor per entry
    /// of [`Mesh::adjacency`], [`crate::hierarchy::Hierarchy::stretch`],
    /// [`cotan::stretched_edge_lengths`]).
    pub(crate) fn compute_with_mass(
        mesh: &Mesh,
        mass: Option<&[f64]>,
        stretch: Option<&[f64]>,
        params: &EigenParams,
        progress: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Eigenbasis, SpectralError> {
        let t = Instant::now();
        // The eigenproblem is solved on the mesh scaled to unit area (the solver's shift and
        // tolerances are absolute numbers), and its answer returned in the input's units:
        // with `x = s·x̂`, `λ = λ̂/s²`, `φ = φ̂/s` (M-orthonormal), `M = s²·M̂`; the cotangent
        // Laplacian does not depend on scale. A mesh in millimetres or in kilometres gets the
        // same basis up to these factors (issue 16, item 1).
        let (unit, s) = mesh.normalized();
        let lengths = match stretch {
            Some(stretch) => cotan::stretched_edge_lengths(&unit, &unit.adjacency(), stretch),
            None => cotan::mollified_edge_lengths(&unit),
        };
        let laplacian = cotan::cotan_laplacian(&unit, &lengths);
        let unit_mass = match mass {
            Some(given) => {
                debug_assert_eq!(given.len(), mesh.num_vertices(), "one mass per vertex");
                given.iter().map(|m| m / (s * s)).collect()
            }
            None => mass::lumped_mass(&unit, &lengths),
        };
        let assembly_seconds = t.elapsed().as_secs_f64();
        let (mut evals, mut evecs, mut info) = eigen::eigen(&laplacian, &unit_mass, params, progress)?;
        if s != 1.0 {
            // ‖Lφ − λMφ‖/‖Mφ‖ has the units of λ.
            info.max_residual /= s * s;
            evals.iter_mut().for_each(|l| *l /= s * s);
            evecs.col_iter_mut().for_each(|c| c.iter_mut().for_each(|x| *x /= s));
        }
        let mass: Vec<f64> = unit_mass.iter().map(|m| m * s * s).collect();
        let area = mass.iter().sum();
        Ok(Eigenbasis { evals, evecs, mass, laplacian, area, info, assembly_seconds })
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.mass.len()
    }

    /// Number of eigenpairs.
    pub fn k(&self) -> usize {
        self.evals.len()
    }
}
