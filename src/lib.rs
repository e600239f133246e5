//! # intrinsym — detection and characterization of intrinsic symmetry
//!
//! An implementation of Mukhopadhyay, Bhandarkar & Porikli, *Detection and Characterization of
//! Intrinsic Symmetry*: the self-maps of a surface that preserve intrinsic distances, including
//! partial, overlapping and pose-hidden ones.
//!
//! ```text
//! mesh ─ validate ─▶ spectral ─▶ (eigenvalues λ, M-orthonormal eigenvectors Φ)
//!                       │
//!           ┌───────────┼───────────────┐
//!       descriptors   distance        (reused by maps)
//!         (WKS)     (biharmonic)
//!           └─────┬─────┘
//!              sampling ─▶ voting ─▶ maps ─▶ characterize ─▶ cluster ─▶ Result
//! ```
//!
//! One module per stage: [`mesh`] (validation, file input), [`spectral`] (cotangent
//! Laplacian, lumped mass, shift-invert block Lanczos), [`descriptors`] (WKS), [`distance`]
//! (biharmonic), [`sampling`] (farthest points), [`voting`] (correspondence space voting),
//! [`maps`] (dense maps, ZoomOut), [`parts`] (partial symmetries between repeated parts,
//! experimental), [`characterize`] (complexity, order), [`cluster`] (groups);
//! [`detect()`] runs them all. [`output`] writes JSON, PLY and reports, [`eval`] scores maps
//! against ground truth, and [`shapes`] generates test shapes with known symmetry.

#![warn(missing_docs)]
// The module docs are for developers and cite private constants and helpers by link: read
// them with `cargo doc --document-private-items`.
#![allow(rustdoc::private_intra_doc_links)]

pub mod characterize;
pub mod cluster;
pub mod descriptors;
pub mod detect;
pub mod distance;
pub mod error;
pub mod hierarchy;
pub mod eval;
pub mod ffi;
pub mod judge;
pub mod maps;
pub mod mesh;
pub mod output;
mod parallel;
pub mod parts;
mod random;
pub mod sampling;
pub mod shapes;
pub mod spectral;
pub mod voting;

pub use detect::{detect, Detection, Kind, Params, Symmetry};
pub use error::Error;
pub use mesh::{Mesh, MeshParams};
pub use spectral::{Eigenbasis, EigenParams};

/// A scratch folder for unit tests inside the build folder (next to the test binary, under
/// `target/`): tests never write outside it.
#[cfg(test)]
pub(crate) fn test_dir(name: &str) -> std::path::PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let dir = exe.parent().expect("a folder").join("intrinsym-test").join(format!("{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder in the build folder");
    dir
}
