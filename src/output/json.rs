//! The JSON report. Schema (documented in the README):
//!
//! ```text
//! { "vertices": n, "faces": m,
//!   "params": { "eigenpairs", "samples", "seed", "restarts", "min_score_ratio", "global_preference", "wks_quantile", "eps", "accept", "polish", "final_polish", "winner_polish", "proxy_vertices", "lift_polish", "hierarchy_vertices", "min_hole", "max_hole", "groups", "parts" },
//!   "timings": { "spectral", "descriptors", "distance", "sampling", "voting", "maps",
//!                "maps_proxy", "maps_profile", "maps_fmap", "maps_refine", "maps_polish", "maps_compose", "maps_lift", "parts",
//!                "congruence", "hierarchy", "lift", "characterize", "cluster", "total" },   // seconds
//!   "continuous": { "dimension": d, "residuals": [floats] },   // d > 0: a continuous family
//!   "components": [ { "vertices", "area", "continuous": { "dimension", "residuals" } } ],
//!                                   // processed components, largest first; area: share
//!   "mesh": { "isolated_vertices", "components", "kept_components", "ignored_component_vertices",
//!             "non_manifold_edges", "degenerate_triangles", "welded_vertices", "collapsed_triangles",
//!             "duplicate_triangles", "closed_holes", "cap_vertices" },
//!   "symmetries": [ { "id", "kind": "global"|"partial", "group", "order", "complexity",
//!                     "distortion", "score", "orientation": "reversing"|"preserving",
//!                     "reversal", "curvature_change", "band_trace", "fixed", "source", "target", "support_pairs": [[a, b], …],
//!                     "region_size", "components": [from, to], "map": [n ints, −1 outside], "confidence": [n floats],
//!                     "fmap": [k_f² floats, row-major], "fmap_size": k_f } ] }
//! ```
//! Vertex indices are those of the input file.

use serde_json::{json, Value};

use crate::detect::{Detection, Params};

/// The report as a JSON value.
pub fn to_json(det: &Detection, params: &Params) -> Value {
    let t = &det.timings;
    let symmetries: Vec<Value> = det
        .symmetries
        .iter()
        .enumerate()
        .map(|(id, s)| {
            let k = s.fmap.nrows();
            let fmap: Vec<f64> = (0..k).flat_map(|i| (0..k).map(move |j| (i, j))).map(|(i, j)| s.fmap[(i, j)]).collect();
            json!({
                "id": id,
                "kind": s.kind.as_str(),
                "group": s.group,
                "order": s.order,
                "complexity": s.complexity,
                "distortion": s.distortion,
                "score": s.verdict.score,
                "orientation": s.verdict.orientation(),
                "reversal": s.verdict.reversal,
                "curvature_change": s.verdict.curvature,
                "band_trace": s.verdict.band_trace,
                "fixed": s.verdict.fixed,
                "source": s.source,
                "target": s.target,
                "support_pairs": s.support_pairs.iter().map(|&(a, b)| [a, b]).collect::<Vec<_>>(),
                "region_size": s.region_size,
                "components": s.components,
                "map": s.map,
                "confidence": s.confidence,
                "fmap": fmap,
                "fmap_size": k,
            })
        })
        .collect();
    json!({
        "vertices": det.vertices,
        "faces": det.faces,
        "continuous": { "dimension": det.continuous.dimension, "residuals": det.continuous.residuals },
        "components": det.components.iter().map(|c| json!({
            "vertices": c.vertices,
            "area": c.area,
            "continuous": { "dimension": c.continuous.dimension, "residuals": c.continuous.residuals },
        })).collect::<Vec<_>>(),
        "mesh": {
            "isolated_vertices": det.mesh.isolated_vertices,
            "components": det.mesh.components,
            "kept_components": det.mesh.kept_components,
            "ignored_component_vertices": det.mesh.ignored_component_vertices,
            "non_manifold_edges": det.mesh.non_manifold_edges,
            "degenerate_triangles": det.mesh.degenerate_triangles,
            "welded_vertices": det.mesh.welded_vertices,
            "collapsed_triangles": det.mesh.collapsed_triangles,
            "duplicate_triangles": det.mesh.duplicate_triangles,
            "closed_holes": det.mesh.closed_holes,
            "cap_vertices": det.mesh.cap_vertices,
        },
        "params": {
            "eigenpairs": params.eigen.k,
            "samples": params.samples,
            "seed": params.seed,
            "restarts": params.restarts,
            "min_score_ratio": params.min_score_ratio,
            "global_preference": params.global_preference,
            "wks_quantile": params.voting.wks_quantile,
            "eps": params.voting.eps,
            "accept": params.maps.accept,
            "polish": params.maps.polish,
            "final_polish": params.maps.final_polish,
            "winner_polish": params.maps.winner_polish,
            "proxy_vertices": params.maps.proxy_vertices,
            "lift_polish": params.maps.lift_polish,
            "hierarchy_vertices": params.hierarchy_vertices,
            "min_hole": params.min_hole,
            "max_hole": params.max_hole,
            "groups": params.groups,
            "parts": params.parts.enabled,
        },
        "timings": {
            "spectral": t.spectral,
            "descriptors": t.descriptors,
            "distance": t.distance,
            "sampling": t.sampling,
            "voting": t.voting,
            "maps": t.maps,
            "maps_profile": t.maps_profile,
            "maps_fmap": t.maps_fmap,
            "maps_refine": t.maps_refine,
            "maps_polish": t.maps_polish,
            "maps_compose": t.maps_compose,
            "maps_proxy": t.maps_proxy,
            "maps_lift": t.maps_lift,
            "parts": t.parts,
            "congruence": t.congruence,
            "hierarchy": t.hierarchy,
            "lift": t.lift,
            "characterize": t.characterize,
            "cluster": t.cluster,
            "total": t.total,
        },
        "symmetries": symmetries,
    })
}
