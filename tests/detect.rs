//! End-to-end detection on generated shapes with known symmetry.
//!
//! Quadrupeds are built at icosphere level 4 (2,562 vertices) to keep the suite fast; the
//! evaluation binary (`intrinsym-eval --generated`) reports the 10k-vertex versions. Thresholds
//! sit a few points under the measured values (posed 93.3%, 0.2% noise 95.4%, 0.5% noise
//! 96.6%, rest 100% at acc@0.05) so that they catch regressions without flaking.

use intrinsym::shapes::{self, Pose};
use intrinsym::{detect, eval, Error, Kind, Mesh, MeshParams, Params};

fn mirror_truth(c: &shapes::Creature) -> Vec<(usize, Vec<usize>)> {
    (0..c.mesh.num_vertices()).map(|v| (v, vec![c.mirror[v] as usize])).collect()
}

fn run(c: &shapes::Creature) -> intrinsym::Detection {
    detect(&c.mesh, &Params::default(), &mut |_| true).unwrap()
}

/// The worst of the 12 ordered leg → leg maps, each scored by the best reported symmetry at
/// acc@0.1 (a leg is itself mirror-symmetric, so either image counts): `(acc, i, j)`.
fn worst_leg_map(c: &shapes::Creature, d: &intrinsym::Detection) -> (f64, usize, usize) {
    let mut worst = (f64::INFINITY, 0, 0);
    for i in 0..4 {
        for j in (0..4).filter(|&j| j != i) {
            let best = d.symmetries.iter().map(|s| eval::accuracy(&c.mesh, &s.map, &c.limb_truth(i, j), &[0.1])[0]).fold(0.0, f64::max);
            if best < worst.0 {
                worst = (best, i, j);
            }
        }
    }
    worst
}

/// acc@(0.05, 0.10) of the strongest symmetry against the left–right mirror.
fn strongest_mirror_accuracy(c: &shapes::Creature) -> (intrinsym::Detection, Vec<f64>) {
    let d = run(c);
    assert!(!d.symmetries.is_empty(), "no symmetry found");
    let acc = eval::accuracy(&c.mesh, &d.symmetries[0].map, &mirror_truth(c), &[0.05, 0.10]);
    (d, acc)
}

#[test]
fn rest_quadruped_mirror_is_exact() {
    let c = shapes::quadruped(4, Pose::Rest, 0.0, 0);
    let (d, acc) = strongest_mirror_accuracy(&c);
    assert!(acc[0] >= 0.98, "acc@0.05 {acc:?}");
    let s = &d.symmetries[0];
    assert_eq!(s.kind, Kind::Global);
    assert_eq!(s.order, 2);
    assert!(s.complexity < 0.5, "an exact isometry has a near-diagonal C: {}", s.complexity);
}

#[test]
fn posed_quadruped_mirror() {
    let c = shapes::quadruped(4, Pose::Walking, 0.0, 0);
    let (d, acc) = strongest_mirror_accuracy(&c);
    assert!(acc[0] >= 0.90, "acc@0.05 {acc:?}");
    let s = &d.symmetries[0];
    assert_eq!(s.kind, Kind::Global);
    assert_eq!(s.order, 2, "a mirror is an involution");
    // Every vertex mapped, to a valid vertex; confidences in [0, 1].
    assert!(s.map.iter().all(|&t| t >= 0 && (t as usize) < c.mesh.num_vertices()));
    assert!(s.confidence.iter().all(|x| (0.0..=1.0).contains(x)));
    assert_eq!(s.fmap.nrows(), Params::default().maps.fmap_size);
    // T∘T ≈ id: most vertices come back within 0.05·√area.
    let back: Vec<i64> = (0..s.map.len()).map(|v| s.map[s.map[v] as usize]).collect();
    let identity: Vec<(usize, Vec<usize>)> = (0..s.map.len()).map(|v| (v, vec![v])).collect();
    let round_trip = eval::accuracy(&c.mesh, &back, &identity, &[0.05])[0];
    assert!(round_trip >= 0.9, "T∘T within 0.05√A for {round_trip}");
    // Every one of the 12 ordered leg → leg maps is covered by a reported symmetry: left↔right
    // by the mirror, front↔hind by the front↔back near-symmetry, the diagonals by their
    // composition. Measured 0.85–1.00 at acc@0.1 (the issue asks 0.8).
    let (worst, i, j) = worst_leg_map(&c, &d);
    assert!(worst >= 0.75, "leg {i} -> leg {j}: {worst}");
}

#[test]
fn posed_quadruped_with_noise() {
    // Noise of 0.2% and 0.5% of the bounding-box diagonal, seven noise seeds each. Measured
    // (session 4): the mirror is reported in every seed, with acc@0.05 of 0.931–0.964 (0.2%)
    // and 0.957–0.973 (0.5%). (Session 1 found it in 5 of 7 seeds at 0.2%: this generator's
    // front↔back near-symmetry out-voted it.) The test demands every seed at ≥ 0.9.
    for noise in [0.002, 0.005] {
        let mut hits = Vec::new();
        for seed in 0..7 {
            let c = shapes::quadruped(4, Pose::Walking, noise, seed);
            let d = run(&c);
            let best = d.symmetries.iter().map(|s| eval::accuracy(&c.mesh, &s.map, &mirror_truth(&c), &[0.05])[0]).fold(0.0, f64::max);
            hits.push(best);
        }
        assert!(hits.iter().all(|&a| a >= 0.9), "noise {noise}: acc@0.05 per seed {hits:?}");
    }
}

/// The maps stage on a proxy (`maps::proxy`): a 2.5k quadruped with a 1,000-vertex proxy,
/// the ratio the default 6,000 gives a 50k mesh (12× fewer at 50k; 2.6× here, the smallest
/// shape that still has legs to map). Measured at 0.2% noise, seeds 0–3: mirror 0.92–0.97
/// acc@0.05, every leg map 0.83–1.00 acc@0.1; the test demands 0.88 and 0.75. Every vertex
/// of the mesh gets an image (the lift), within the mesh.
#[test]
fn maps_on_a_proxy_are_lifted_to_every_vertex() {
    let mut params = Params::default();
    params.maps.proxy_vertices = 1000;
    for seed in 0..4 {
        let c = shapes::quadruped(4, Pose::Walking, 0.002, seed);
        let n = c.mesh.num_vertices();
        assert!(intrinsym::maps::proxy::wanted(n, &params.maps));
        let d = detect(&c.mesh, &params, &mut |_| true).unwrap();
        assert!(d.timings.maps_proxy > 0.0 && d.timings.maps_lift > 0.0);
        // Every global map is lifted to every vertex. The mirror is among them; on this
        // 1,000-vertex proxy of a 2,562-vertex mesh it is not always first: the lift from so
        // coarse a proxy distorts it (0.026 on seed 0) more than the quadruped's front↔back
        // near-symmetry (0.021), and the judge ranks by distortion among reflections.
        for s in d.symmetries.iter().filter(|s| s.kind == Kind::Global) {
            assert!(s.map.iter().all(|&t| t >= 0 && (t as usize) < n));
        }
        let acc = d.symmetries.iter().map(|s| eval::accuracy(&c.mesh, &s.map, &mirror_truth(&c), &[0.05])[0]).fold(0.0, f64::max);
        assert!(acc >= 0.88, "seed {seed}: mirror acc@0.05 {acc}");
        let (worst, i, j) = worst_leg_map(&c, &d);
        assert!(worst >= 0.75, "seed {seed}: leg {i} -> leg {j}: {worst}");
    }
}

/// The polish of the lifted maps on the mesh itself (`MapParams::lift_polish`): on a
/// 1,000-vertex proxy of the 2.5k walking quadruped (0.2% noise) the lifted mirror is only as
/// precise as the proxy's coarse graph measures geodesics; polished on the mesh it is more
/// precise. Measured, seeds 0–3, the best map's mirror acc@0.02 without / with four passes:
/// 0.895 / 0.952, 0.875 / 0.948, 0.882 / 0.955, 0.901 / 0.951 (acc@0.05 0.97–0.98 → 0.98–0.99).
/// The test demands a gain of 0.03 at every seed and 0.93.
#[test]
fn lifted_maps_polished_on_the_mesh_are_more_precise() {
    let mut params = Params::default();
    params.maps.proxy_vertices = 1000;
    // Without the winner's passes, which also polish on the mesh (`MapParams::winner_polish`).
    params.maps.winner_polish = 0;
    for seed in 0..4 {
        let c = shapes::quadruped(4, Pose::Walking, 0.002, seed);
        let truth = mirror_truth(&c);
        let mirror = |lift_polish: usize| {
            let mut p = params.clone();
            p.maps.lift_polish = lift_polish;
            let d = detect(&c.mesh, &p, &mut |_| true).unwrap();
            let acc = |s: &intrinsym::Symmetry, r: f64| eval::accuracy(&c.mesh, &s.map, &truth, &[r])[0];
            d.symmetries.iter().map(|s| acc(s, 0.02)).fold(0.0, f64::max)
        };
        let (without, with) = (mirror(0), mirror(4));
        assert!(with >= 0.93 && with >= without + 0.03, "seed {seed}: mirror acc@0.02 {without} without the polish on the mesh, {with} with it");
    }
}

/// The 10k noisy quadrupeds at full resolution (the maps on the 6,000-vertex proxy): the
/// mirror is the strongest symmetry and all 12 leg maps are found, in every noise case. Before
/// new symmetries were refined ahead of variants of found ones, the front↔back map (and with
/// it 8 of the leg maps) was lost in 1 of these 8 cases on the full mesh and 4 of 8 on a
/// 5,000-vertex proxy. Measured: mirror 0.963–0.986 acc@0.05, leg maps ≥ 0.94 acc@0.1.
#[test]
fn noisy_quadrupeds_keep_every_leg_map() {
    let mut params = Params::default();
    params.hierarchy_vertices = 0;
    for noise in [0.002, 0.005] {
        for seed in 0..4 {
            let c = shapes::quadruped(5, Pose::Walking, noise, seed);
            let d = detect(&c.mesh, &params, &mut |_| true).unwrap();
            let first = eval::accuracy(&c.mesh, &d.symmetries[0].map, &mirror_truth(&c), &[0.05])[0];
            assert!(first >= 0.93, "noise {noise} seed {seed}: strongest symmetry's mirror acc@0.05 {first}");
            let (worst, i, j) = worst_leg_map(&c, &d);
            assert!(worst >= 0.8, "noise {noise} seed {seed}: leg {i} -> leg {j}: {worst}");
        }
    }
}

#[test]
fn deterministic_and_scale_invariant() {
    let c = shapes::quadruped(4, Pose::Walking, 0.0, 0);
    let a = run(&c);
    let b = run(&c);
    assert_eq!(a.symmetries.len(), b.symmetries.len());
    for (x, y) in a.symmetries.iter().zip(&b.symmetries) {
        assert_eq!(x.map, y.map);
        assert_eq!(x.complexity, y.complexity);
    }
    // Scaled by 7.5: thresholds are relative, so the strongest map barely changes.
    let scaled: Vec<[f64; 3]> = c.mesh.vertices.iter().map(|p| p.map(|x| 7.5 * x)).collect();
    let mesh = Mesh::new(scaled, c.mesh.triangles.clone(), &MeshParams::default()).unwrap();
    let s = detect(&mesh, &Params::default(), &mut |_| true).unwrap();
    let acc = eval::accuracy(&mesh, &s.symmetries[0].map, &mirror_truth(&c), &[0.05])[0];
    assert!(acc >= 0.9, "scaled: {acc}");
}

#[test]
fn results_use_input_indices() {
    // An isolated vertex first and a small second component last (under 1% of the animal's
    // area): both ignored, and every map entry refers to input indices (the isolated vertex
    // maps to −1).
    let c = shapes::quadruped(4, Pose::Rest, 0.0, 0);
    let n = c.mesh.num_vertices() as u32;
    let mut v = vec![[50.0, 50.0, 50.0]];
    v.extend(c.mesh.vertices.iter().copied());
    v.extend([[90.0, 0.0, 0.0], [90.01, 0.0, 0.0], [90.0, 0.01, 0.0], [90.0, 0.0, 0.01]]);
    let mut t: Vec<[u32; 3]> = c.mesh.triangles.iter().map(|f| f.map(|i| i + 1)).collect();
    let o = n + 1;
    t.extend([[o, o + 2, o + 1], [o, o + 1, o + 3], [o + 1, o + 2, o + 3], [o, o + 3, o + 2]]);
    let mesh = Mesh::new(v, t, &MeshParams::default()).unwrap();
    assert_eq!(mesh.info.isolated_vertices, 1);
    assert_eq!(mesh.info.ignored_component_vertices, 4);
    let d = detect(&mesh, &Params::default(), &mut |_| true).unwrap();
    assert_eq!(d.vertices, n as usize + 5);
    let s = &d.symmetries[0];
    assert_eq!(s.map.len(), n as usize + 5);
    assert_eq!(s.map[0], -1);
    assert!(s.map[n as usize + 1..].iter().all(|&x| x == -1));
    // In input indices the map is the mirror shifted by one (the isolated vertex came first).
    let exact = (0..n as usize).filter(|&x| s.map[x + 1] == c.mirror[x] as i64 + 1).count();
    assert!(exact as f64 >= 0.98 * n as f64, "{exact} of {n} exact mirror images");
}

#[test]
fn cancel_stops_with_an_error() {
    let c = shapes::quadruped(4, Pose::Rest, 0.0, 0);
    let mut calls = 0;
    let e = detect(&c.mesh, &Params::default(), &mut |f| {
        calls += 1;
        f < 0.3
    })
    .unwrap_err();
    assert!(matches!(e, Error::Cancelled { stage: "eigenbasis" }), "{e}");
    assert!(calls > 1);
}

/// Stopping at the final call (fraction 1) cancels too, and the error names the stage
/// (issue 16, item 11: it was ignored, and every cancel said "eigensolver").
#[test]
fn cancel_at_the_last_call_and_the_stage_is_named() {
    let c = shapes::quadruped(3, Pose::Rest, 0.0, 0);
    let e = detect(&c.mesh, &Params::default(), &mut |f| f < 1.0).unwrap_err();
    assert!(matches!(e, Error::Cancelled { stage: "report" }), "{e}");
    assert!(e.to_string().contains("report") && !e.to_string().contains("eigensolver"), "{e}");
    let e = detect(&c.mesh, &Params::default(), &mut |f| f < 0.7).unwrap_err();
    assert!(matches!(e, Error::Cancelled { stage: "hypotheses" }), "{e}");
    // The winner's further passes (`MapParams::winner_polish`) ask before each pass.
    let e = detect(&c.mesh, &Params::default(), &mut |f| f < 0.98).unwrap_err();
    assert!(matches!(e, Error::Cancelled { stage: "polish" }), "{e}");
}

/// A detection started from inside another's progress callback returns an error at once
/// instead of deadlocking (issue 16, item 10), and the outer detection completes.
#[test]
fn a_detection_inside_the_progress_callback_is_refused_not_deadlocked() {
    let c = shapes::quadruped(3, Pose::Rest, 0.0, 0);
    let mut inner = Vec::new();
    let outer = detect(&c.mesh, &Params::default(), &mut |_| {
        if inner.is_empty() {
            inner.push(detect(&c.mesh, &Params::default(), &mut |_| true).map(|d| d.symmetries.len()));
        }
        true
    });
    assert!(outer.is_ok_and(|d| !d.symmetries.is_empty()));
    assert!(matches!(inner[0], Err(Error::Reentrant)), "{:?}", inner[0]);
    // And after it, detection works again on this thread.
    assert!(detect(&c.mesh, &Params::default(), &mut |_| true).is_ok());
}

#[test]
fn json_report_has_the_documented_schema() {
    let c = shapes::quadruped(4, Pose::Rest, 0.0, 0);
    let params = Params::default();
    let d = detect(&c.mesh, &params, &mut |_| true).unwrap();
    let j = intrinsym::output::json::to_json(&d, &params);
    assert_eq!(j["vertices"], c.mesh.num_vertices());
    assert!(j["timings"]["total"].as_f64().unwrap() > 0.0);
    let s = &j["symmetries"][0];
    for key in ["id", "kind", "group", "complexity", "distortion", "source", "target", "support_pairs", "region_size", "components", "map", "confidence", "fmap", "fmap_size", "order"] {
        assert!(!s[key].is_null(), "missing {key}");
    }
    let k = s["fmap_size"].as_u64().unwrap() as usize;
    assert_eq!(s["fmap"].as_array().unwrap().len(), k * k);
    // What validation found, and the continuous-symmetry test (issue 16, items 2-4; issue 14).
    for key in ["isolated_vertices", "components", "kept_components", "ignored_component_vertices", "non_manifold_edges", "degenerate_triangles", "welded_vertices", "collapsed_triangles", "duplicate_triangles", "closed_holes", "cap_vertices"] {
        assert!(j["mesh"][key].is_u64(), "missing mesh.{key}");
    }
    assert_eq!(j["mesh"]["components"], 1);
    assert_eq!(j["components"].as_array().map(Vec::len), Some(1));
    assert_eq!(j["components"][0]["vertices"], c.mesh.num_vertices());
    assert_eq!(s["components"], serde_json::json!([0, 0]));
    assert!(j["timings"]["congruence"].is_f64());
    assert_eq!(j["continuous"]["dimension"], 0);
    assert_eq!(s["map"].as_array().unwrap().len(), c.mesh.num_vertices());
    let svg = intrinsym::output::report::svg(&d, "test", None);
    assert!(svg.starts_with("<svg") && svg.contains("symmetry space"));
}

#[test]
fn star_symmetry_group_is_complete() {
    // A flat five-armed star has 19 non-trivial symmetries: 5 mirrors, 4 rotations, and each of
    // the 10 composed with the flip of its flat body. Voting finds a few generators; composition
    // completes the group. Each must be reported with acc@0.05 ≥ 0.93 (measured 0.975–0.996
    // at 10k vertices in session 4, 0.90–0.95 before the geodesic polish; at 2.5k voting's 8
    // candidates hold only one vertical mirror).
    let c = shapes::star(5, 5);
    let d = run(&c);
    for (name, truth) in shapes::star_symmetries(&c, 5) {
        let truth: Vec<(usize, Vec<usize>)> = truth.iter().enumerate().map(|(v, &w)| (v, vec![w as usize])).collect();
        let best = d.symmetries.iter().map(|s| eval::accuracy(&c.mesh, &s.map, &truth, &[0.05])[0]).fold(0.0, f64::max);
        assert!(best >= 0.93, "{name}: best acc@0.05 {best}");
    }
}

/// A narrow animal without legs (body radii 0.12 × 0.4 × 1 in x, y, z; a head and a bent
/// tail along z): its left–right mirror moves points little, as a TOSCA cat's does.
fn narrow_animal(level: u32) -> shapes::Creature {
    let limbs = [
        shapes::Limb { direction: [0.0, 0.3, 1.0], axis: [0.0, 0.3, 1.0], length: 0.5, cap: 0.45, bend: 0.0, bend_axis: [0.0, 1.0, 0.0] },
        shapes::Limb { direction: [0.0, 0.2, -1.0], axis: [0.0, 0.3, -1.0], length: 0.8, cap: 0.3, bend: 0.5, bend_axis: [1.0, 0.0, 0.0] },
    ];
    shapes::creature(level, [0.12, 0.4, 1.0], &limbs, 0.0, 0)
}

/// A mirror that moves points little (a flat, narrow body) is still reported, first: the
/// identity filter is the fraction of fixed points, not the mean displacement (which rejected
/// TOSCA's cats, whose mirror moves points by 0.036–0.042 of the diameter; this body's by
/// 0.086, the thinnest generated body tried by 0.073).
#[test]
fn a_mirror_that_moves_points_little_is_found() {
    let c = narrow_animal(4);
    let (d, acc) = strongest_mirror_accuracy(&c);
    assert!(acc[0] >= 0.85, "acc@0.05 {acc:?}");
    let s = &d.symmetries[0];
    assert!(s.verdict.reverses() && s.verdict.fixed < 0.3, "{:?}", s.verdict);
    // The judge's fixed fraction (the identity filter) sees a mirror, however little it moves
    // points: only the band along the symmetry plane is fixed.
    let n = c.mesh.num_vertices();
    let truth: Vec<i64> = c.mirror.iter().map(|&m| m as i64).collect();
    let judge = intrinsym::judge::Judge::new(&c.mesh.vertices, intrinsym::judge::vertex_normals(&c.mesh), &c.mesh.adjacency(), c.mesh.area().sqrt(), &Default::default());
    let v = judge.judge(&truth, 0.0, 0.04);
    assert!(v.fixed < 0.3 && v.reversal > 0.9, "true mirror of {n} vertices: {v:?}");
}

/// A half-identity (the mirror on the front half, the identity on the back) loses to the
/// mirror before the judge, and detection reports the mirror first, with its type.
#[test]
fn the_judge_prefers_the_mirror_to_a_half_identity() {
    let c = shapes::quadruped(4, Pose::Walking, 0.0, 0);
    let mesh = &c.mesh;
    let judge = intrinsym::judge::Judge::new(&mesh.vertices, intrinsym::judge::vertex_normals(mesh), &mesh.adjacency(), mesh.area().sqrt(), &Default::default());
    let mirror: Vec<i64> = c.mirror.iter().map(|&m| m as i64).collect();
    let half: Vec<i64> = (0..mesh.num_vertices()).map(|v| if c.rest[v][2] > 0.0 { mirror[v] } else { v as i64 }).collect();
    let (m, h) = (judge.judge(&mirror, 0.01, 0.04), judge.judge(&half, 0.01, 0.04));
    assert!(m.reversal > 0.9 && m.fixed < 0.2, "mirror {m:?}");
    assert!(h.fixed > 0.3 && h.coherence() < 0.5 && h.score < 0.5 * m.score, "half-identity {h:?} against {m:?}");
    let d = run(&c);
    let first = &d.symmetries[0];
    assert!(first.verdict.reverses() && first.order == 2, "{:?}", first.verdict);
    assert!(d.symmetries.windows(2).all(|w| w[0].verdict.score >= w[1].verdict.score), "ranked by the judge");
}

/// A shape with no symmetry (limbs of different lengths in directions no map exchanges)
/// gets no global symmetry, and no map anywhere that is the identity (order 1), at 2.5k and
/// at 10k vertices (at 10k a false global map with distortion 0.034 was reported until
/// session 17: it changes the curvature by 0.41, more than any true symmetry of shared/data).
#[test]
fn a_shape_without_symmetry_gets_no_global_symmetry() {
    for level in [4, 5] {
        let c = shapes::lopsided(level);
        let d = run(&c);
        let global: Vec<_> = d.symmetries.iter().filter(|s| s.kind == Kind::Global).map(|s| (s.verdict, s.distortion)).collect();
        assert!(global.is_empty(), "level {level}: global symmetries reported: {global:?}");
        assert!(d.symmetries.iter().all(|s| s.order != 1), "level {level}: an identity reported");
    }
}

/// A mesh whose triangles mix orientations (as users' meshes can) gets the same verdicts: the
/// judge and the orientation operators orient the triangles consistently first.
#[test]
fn mixed_triangle_orientations_do_not_change_the_verdict() {
    let c = shapes::quadruped(4, Pose::Walking, 0.0, 0);
    let mut triangles = c.mesh.triangles.clone();
    for t in triangles.iter_mut().step_by(3) {
        t.swap(0, 1);
    }
    let mixed = Mesh::new(c.mesh.vertices.clone(), triangles, &MeshParams::default()).unwrap();
    let (a, b) = (run(&c), detect(&mixed, &Params::default(), &mut |_| true).unwrap());
    assert_eq!(a.symmetries.len(), b.symmetries.len());
    for (s, t) in a.symmetries.iter().zip(&b.symmetries) {
        assert_eq!(s.map, t.map);
        // The same maps; the score's distortion is measured in the biharmonic embedding, whose
        // sums run in another order on the flipped triangles (differences of 3e-11 seen).
        assert!((s.verdict.score - t.verdict.score).abs() < 1e-9, "{:?} {:?}", s.verdict, t.verdict);
        assert_eq!((s.verdict.reversal, s.verdict.fixed, s.verdict.coverage), (t.verdict.reversal, t.verdict.fixed, t.verdict.coverage));
    }
}

/// An ellipsoid with three distinct axes has exactly 7 symmetries besides the identity: the
/// three mirrors, the three half-turns and the antipodal map (issue 14, precision). Each is
/// found, each once, and nothing else is reported.
#[test]
fn an_ellipsoid_reports_its_seven_symmetries_and_nothing_else() {
    let mesh = shapes::ellipsoid(4, [1.0, 0.75, 0.5]);
    let d = detect(&mesh, &Params::default(), &mut |_| true).unwrap();
    assert_eq!(d.continuous.dimension, 0, "{:?}", d.continuous);
    let flips: Vec<[bool; 3]> = (1..8u32).map(|b| [b & 1 != 0, b & 2 != 0, b & 4 != 0]).collect();
    let truths: Vec<Vec<(usize, Vec<usize>)>> = flips
        .iter()
        .map(|&f| shapes::sign_flip_map(&mesh, f).into_iter().enumerate().map(|(v, w)| (v, vec![w.expect("a partner") as usize])).collect())
        .collect();
    let mut matched = vec![Vec::new(); flips.len()];
    for (i, s) in d.symmetries.iter().enumerate() {
        let accs: Vec<f64> = truths.iter().map(|t| eval::accuracy(&mesh, &s.map, t, &[0.05])[0]).collect();
        let (best, acc) = accs.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)).unwrap();
        assert!(*acc > 0.9, "symmetry #{i} is none of the seven: acc {accs:?}");
        // A reflection through a plane or the antipodal map (odd number of flips) reverses.
        let reversing = flips[best].iter().filter(|&&f| f).count() % 2 == 1;
        assert_eq!(s.verdict.reverses(), reversing, "#{i} ({:?}) has the wrong orientation type", flips[best]);
        matched[best].push(i);
    }
    assert!(matched.iter().all(|m| m.len() == 1), "each of the seven exactly once: {matched:?}");
}

/// A sphere and a torus of revolution have a continuous family of isometries: the detection
/// says so (dimension 3 and 1) and lists one map per orientation type instead of filling the
/// cap with samples of the family (issue 14, precision).
#[test]
fn continuous_symmetries_are_reported_as_such() {
    for (name, mesh, dimension) in [("sphere", shapes::icosphere(4), 3), ("torus of revolution", shapes::torus_of_revolution(72, 28, 0.4), 1)] {
        let d = detect(&mesh, &Params::default(), &mut |_| true).unwrap();
        assert_eq!(d.continuous.dimension, dimension, "{name}: {:?}", d.continuous);
        assert!(d.continuous.residuals[0] < 0.01, "{name}: {:?}", d.continuous);
        assert!((1..=2).contains(&d.symmetries.len()), "{name}: {} symmetries", d.symmetries.len());
        let reversing = d.symmetries.iter().filter(|s| s.verdict.reverses()).count();
        assert!(reversing <= 1 && d.symmetries.len() - reversing <= 1, "{name}: one map per orientation type");
    }
}

/// Results do not depend on the mesh's units or position (issue 16, item 1): the same
/// symmetries, with maps that agree on nearly every vertex, at scales 1e-9 … 1e9 and under a
/// 1e6 translation.
#[test]
fn units_and_position_do_not_change_the_result() {
    let c = shapes::quadruped(3, Pose::Walking, 0.0, 0);
    let base = run(&c);
    for (scale, shift) in [(1e-9, 0.0), (1e-3, 0.0), (1e3, 0.0), (1e9, 0.0), (1.0, 1e6)] {
        let v: Vec<[f64; 3]> = c.mesh.vertices.iter().map(|p| p.map(|x| x * scale + shift)).collect();
        let mesh = Mesh::new(v, c.mesh.triangles.clone(), &MeshParams::default()).unwrap();
        let d = detect(&mesh, &Params::default(), &mut |_| true).unwrap();
        assert_eq!(d.symmetries.len(), base.symmetries.len(), "scale {scale:e}, shift {shift:e}");
        for (s, t) in d.symmetries.iter().zip(&base.symmetries) {
            let same = s.map.iter().zip(&t.map).filter(|(a, b)| a == b).count();
            assert!(same as f64 >= 0.98 * s.map.len() as f64, "scale {scale:e}, shift {shift:e}: {same} of {} vertices agree", s.map.len());
        }
    }
}

/// An STL-style triangle soup (every triangle with its own three vertices) is welded and
/// gets the symmetries of the mesh it came from, on every input vertex (issue 16, item 3:
/// it gave "0 symmetries" from one triangle).
#[test]
fn a_triangle_soup_is_welded_and_every_vertex_is_mapped() {
    let c = shapes::quadruped(3, Pose::Rest, 0.0, 0);
    let base = run(&c);
    let vertices: Vec<[f64; 3]> = c.mesh.triangles.iter().flat_map(|t| t.map(|v| c.mesh.vertices[v as usize])).collect();
    let triangles: Vec<[u32; 3]> = (0..c.mesh.num_triangles() as u32).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect();
    let soup = Mesh::new(vertices.clone(), triangles, &MeshParams::default()).unwrap();
    assert_eq!(soup.info.welded_vertices, vertices.len() - c.mesh.num_vertices());
    let d = detect(&soup, &Params::default(), &mut |_| true).unwrap();
    assert_eq!(d.mesh.welded_vertices, soup.info.welded_vertices);
    assert_eq!(d.symmetries.len(), base.symmetries.len());
    // The strongest map, read on the soup's vertices, is the mirror.
    let position = |v: i64| vertices[v as usize];
    let s = &d.symmetries[0];
    assert!(s.map.iter().all(|&m| m >= 0), "every soup vertex has an image");
    let mirrored = (0..vertices.len()).filter(|&v| {
        let (p, q) = (vertices[v], position(s.map[v]));
        (p[0] + q[0]).abs() < 1e-9 && (p[1] - q[1]).abs() < 1e-9 && (p[2] - q[2]).abs() < 1e-9
    });
    assert!(mirrored.count() as f64 > 0.95 * vertices.len() as f64);
}

/// A shoe and its partner, the partner tessellated differently (the shoe's triangles split in
/// four), side by side; the swap's ground truth on the shoe's vertices and their copies.
fn shoes(mirrored: bool) -> (Mesh, Vec<(usize, Vec<usize>)>) {
    let a = shapes::lopsided(4).mesh;
    let b = shapes::subdivide(&a, &MeshParams::default()).unwrap();
    let n = a.num_vertices();
    let mut truth: Vec<(usize, Vec<usize>)> = (0..n).map(|v| (v, vec![n + v])).collect();
    truth.extend((0..n).map(|v| (n + v, vec![v])));
    (shapes::side_by_side(&a, &b, mirrored, 0.5), truth)
}

/// A pair of shoes (issue 16, item 4): an asymmetric shape and its mirror image, two
/// components tessellated differently. Each is processed, and the strongest symmetry is the
/// swap, an orientation-reversing involution defined on both (acc@0.035 of the pair's √area,
/// 0.05 of one shoe's: measured 0.989).
#[test]
fn a_pair_of_mirror_images_is_swapped_by_a_reflection() {
    let (mesh, truth) = shoes(true);
    let d = detect(&mesh, &Params::default(), &mut |_| true).unwrap();
    assert_eq!(d.components.len(), 2);
    assert!(d.components.iter().all(|c| (c.area - 0.5).abs() < 1e-6), "{:?}", d.components);
    let s = &d.symmetries[0];
    assert_eq!((s.components, s.kind, s.order), ([0, 1], Kind::Global, 2), "{:?}", d.symmetries.iter().map(|s| (s.components, s.kind, s.verdict.score)).collect::<Vec<_>>());
    assert!(s.verdict.reverses(), "a mirror image: {:?}", s.verdict);
    let acc = eval::accuracy(&mesh, &s.map, &truth, &[0.035])[0];
    assert!(acc > 0.95, "swap acc {acc}");
    assert!(s.map.iter().all(|&w| w >= 0), "defined on both components");
    // No other global symmetry: neither shoe has one of its own.
    assert_eq!(d.symmetries.iter().filter(|s| s.kind == Kind::Global).count(), 1);
}

/// Two copies of one shape are swapped by an orientation-preserving map (measured acc 0.989).
#[test]
fn two_copies_are_swapped_by_an_orientation_preserving_map() {
    let (mesh, truth) = shoes(false);
    let d = detect(&mesh, &Params::default(), &mut |_| true).unwrap();
    let s = &d.symmetries[0];
    assert_eq!(s.components, [0, 1]);
    assert!(!s.verdict.reverses(), "a copy: {:?}", s.verdict);
    let acc = eval::accuracy(&mesh, &s.map, &truth, &[0.035])[0];
    assert!(acc > 0.95, "swap acc {acc}");
}

/// Components that are not congruent are each processed (the ellipsoid's three mirrors found
/// on its component), and no map between them is reported.
#[test]
fn components_that_are_not_congruent_are_each_processed() {
    let blob = shapes::lopsided(4).mesh;
    let ellipsoid = shapes::ellipsoid(4, [1.0, 0.75, 0.5]);
    let n = blob.num_vertices() as u32;
    let mut vertices = blob.vertices.clone();
    vertices.extend(ellipsoid.vertices.iter().map(|&[x, y, z]| [x + 5.0, y, z]));
    let mut triangles = blob.triangles.clone();
    triangles.extend(ellipsoid.triangles.iter().map(|t| t.map(|v| v + n)));
    let mesh = Mesh::new(vertices, triangles, &MeshParams::default()).unwrap();
    let d = detect(&mesh, &Params::default(), &mut |_| true).unwrap();
    assert_eq!(d.components.len(), 2);
    assert!(d.symmetries.iter().all(|s| s.components[0] == s.components[1]), "no map between different shapes");
    // The ellipsoid's symmetries (its vertices come after the blob's) stay on it.
    let on_ellipsoid: Vec<_> = d.symmetries.iter().filter(|s| s.map[n as usize..].iter().any(|&w| w >= 0)).collect();
    assert!(on_ellipsoid.len() >= 3, "the ellipsoid's symmetries: {}", on_ellipsoid.len());
    for s in &on_ellipsoid {
        assert!((0..n as usize).all(|v| s.map[v] < 0), "a map of the ellipsoid leaves the blob unmapped");
        assert_eq!(s.kind, Kind::Partial, "one component of two is not the whole mesh");
    }
}

/// Small components of meaningful area (a single large triangle, a tetrahedron) beside a shape
/// are processed without failing, and the shape's own symmetry is still found on it.
#[test]
fn tiny_components_beside_a_shape_do_not_break_detection() {
    let c = shapes::quadruped(4, Pose::Rest, 0.0, 0);
    let mut vertices = c.mesh.vertices.clone();
    let mut triangles = c.mesh.triangles.clone();
    let n = vertices.len() as u32;
    // A triangle and a tetrahedron, each above 1% of the animal's area, far away.
    vertices.extend([[10.0, 0.0, 0.0], [11.5, 0.0, 0.0], [10.0, 1.5, 0.0]]);
    triangles.push([n, n + 1, n + 2]);
    vertices.extend([[20.0, 0.0, 0.0], [21.0, 0.0, 0.0], [20.0, 1.0, 0.0], [20.0, 0.0, 1.0]]);
    triangles.extend([[n + 3, n + 5, n + 4], [n + 3, n + 4, n + 6], [n + 3, n + 6, n + 5], [n + 4, n + 5, n + 6]]);
    let mesh = Mesh::new(vertices, triangles, &MeshParams::default()).unwrap();
    assert_eq!(mesh.info.kept_components, 3);
    let d = detect(&mesh, &Params::default(), &mut |_| true).unwrap();
    assert_eq!(d.components.len(), 3);
    let s = &d.symmetries[0];
    assert_eq!(s.components, [0, 0]);
    let truth = mirror_truth(&c);
    let acc = eval::accuracy(&mesh, &s.map, &truth, &[0.05])[0];
    assert!(acc > 0.9, "the animal's mirror: {acc}");
}

/// Issue 17: a large mesh is detected on a coarse mesh (`hierarchy`), and legs thinner than the
/// coarse mesh's spacing neither vanish nor lose their maps. An animal with four long, thin
/// legs (cap 0.12 rad: a leg's circumference is about 2.5% of √area) at 41k vertices, on a
/// coarse mesh of 2000 (spacing about 2.4% of √area): every leg keeps coarse vertices, and
/// the lifted mirror maps each leg onto its mirror leg.
#[test]
fn thin_legs_survive_the_hierarchy() {
    let x = [1.0, 0.0, 0.0];
    let leg = |sx: f64, sz: f64| shapes::Limb { direction: [0.55 * sx, -0.75, 0.55 * sz], axis: [0.0, -1.0, 0.0], length: 1.6, cap: 0.12, bend: 0.0, bend_axis: x };
    let c = shapes::creature(6, [0.5, 0.45, 1.0], &[leg(1.0, 1.0), leg(-1.0, 1.0), leg(1.0, -1.0), leg(-1.0, -1.0)], 0.0, 0);
    let mesh = &c.mesh;
    let h = intrinsym::hierarchy::Hierarchy::new(mesh, 2000).unwrap();
    for j in 0..4 {
        let on_leg = h.seeds.iter().filter(|&&s| c.limb[s] == j).count();
        assert!(on_leg >= 20, "leg {j} keeps {on_leg} coarse vertices");
    }
    let mut params = Params::default();
    params.hierarchy_vertices = 2000;
    let d = detect(mesh, &params, &mut |_| true).unwrap();
    assert!(d.timings.hierarchy > 0.0, "detected on the hierarchy");
    // The body is symmetric front to back too: the left–right mirror is one of the reported.
    let legs: Vec<(usize, Vec<usize>)> = (0..mesh.num_vertices()).filter(|&v| c.limb[v] < 4).map(|v| (v, vec![c.mirror[v] as usize])).collect();
    let acc = d.symmetries.iter().map(|s| eval::accuracy(mesh, &s.map, &legs, &[0.05])[0]).fold(0.0, f64::max);
    assert!(acc > 0.9, "the mirror on the legs: {acc}");
}

/// Noisy quadrupeds at 41k vertices with default parameters, so detected on the hierarchy's
/// 6,000-vertex coarse mesh (`hierarchy`): the mirror is found in every case, and all 12 leg
/// maps are (measured: mirror 0.955–0.98 acc@0.05, leg maps ≥ 0.909 acc@0.1); it is the
/// strongest symmetry in 6 of the 8: on noise 0.005 seeds 0 and 1 the generated animal's
/// front↔back near-mirror (a reflection too) ranks first, by judge scores 0.317 against
/// 0.308 and 0.383 against 0.359. The judge's reversal there rests on 46–49 stencils: on
/// these noisy 41k-vertex meshes most stencil candidates have no well-spread pair in their
/// first ring beyond the reach (see `docs/accuracy.md`, session 18; seed 0 ranked the mirror
/// first until the polish stopped trusting identity parts). The global maps' reported scores
/// (the fine mesh's judge) keep `Params::min_score_ratio` of the strongest.
#[test]
fn noisy_quadrupeds_on_the_hierarchy() {
    let mut first_is_mirror = 0;
    for noise in [0.002, 0.005] {
        for seed in 0..4 {
            let c = shapes::quadruped(6, Pose::Walking, noise, seed);
            let d = run(&c);
            assert!(d.timings.hierarchy > 0.0);
            // The maps are reported with the fine mesh's scores, and none of the global ones
            // scores below `min_score_ratio` of the strongest.
            let global: Vec<f64> = d.symmetries.iter().filter(|s| s.kind == Kind::Global).map(|s| s.verdict.score).collect();
            let top = global.iter().copied().fold(0.0, f64::max);
            assert!(global.iter().all(|&g| g >= Params::default().min_score_ratio * top), "noise {noise} seed {seed}: scores {global:?}");
            let accs: Vec<f64> = d.symmetries.iter().map(|s| eval::accuracy(&c.mesh, &s.map, &mirror_truth(&c), &[0.05])[0]).collect();
            let best = accs.iter().copied().fold(0.0, f64::max);
            assert!(best >= 0.93, "noise {noise} seed {seed}: mirror acc@0.05 {best}");
            first_is_mirror += usize::from(accs[0] >= 0.93);
            let (worst, i, j) = worst_leg_map(&c, &d);
            assert!(worst >= 0.8, "noise {noise} seed {seed}: leg {i} -> leg {j}: {worst}");
        }
    }
    assert!(first_is_mirror >= 6, "the mirror first in {first_is_mirror} of 8");
}

/// On the hierarchy, progress moves inside the simplification (several calls below 10%) and
/// cancelling there stops with the stage named; progress never goes back.
#[test]
fn the_hierarchy_reports_progress_and_can_be_cancelled() {
    let c = shapes::quadruped(6, Pose::Walking, 0.0, 0);
    let mut calls = Vec::new();
    let d = detect(&c.mesh, &Params::default(), &mut |f| {
        calls.push(f);
        true
    });
    assert!(d.is_ok());
    assert!(calls.windows(2).all(|w| w[1] >= w[0]), "progress went back");
    assert!(calls.iter().filter(|&&f| f > 0.0 && f < 0.1).count() >= 3, "steady progress while simplifying: {:?}", &calls[..calls.len().min(12)]);
    assert_eq!(calls.last(), Some(&1.0));
    let e = detect(&c.mesh, &Params::default(), &mut |f| f <= 0.0 || f >= 0.1).unwrap_err();
    assert!(matches!(e, Error::Cancelled { stage: "hierarchy" }), "{e:?}");
}

/// The posed directed quadruped with 0.5% noise (10k vertices, three noise seeds) keeps its
/// left–right mirror among the reported symmetries (measured 0.983–0.985 acc@0.05), and no
/// global map of order 3 or more is reported: the mirror is its only global symmetry. Session
/// 19: projecting the refinement's last ZoomOut onto involutions raised shared/data by 0.3
/// points and passed every other test, but lost this mirror on seed 1 (0.98 → 0.13) and
/// reported global maps of orders 10 and 7 there. Session 34 (the legs made round): seed 2
/// reported two sloppy front↔back maps as rotations of order 8, an artefact of the order test's
/// tolerance growing linearly along the orbit; it stops growing after two steps now
/// (`characterize::order`).
#[test]
fn noisy_directed_quadrupeds_keep_their_mirror() {
    for seed in 1..=3 {
        let c = shapes::directed_quadruped(5, Pose::Walking, 0.005, seed);
        let d = run(&c);
        let best = d.symmetries.iter().map(|s| eval::accuracy(&c.mesh, &s.map, &mirror_truth(&c), &[0.05])[0]).fold(0.0, f64::max);
        assert!(best >= 0.9, "seed {seed}: mirror acc@0.05 {best}");
        let orders: Vec<usize> = d.symmetries.iter().filter(|s| s.kind == Kind::Global).map(|s| s.order).collect();
        assert!(orders.iter().all(|&o| o <= 2), "seed {seed}: global symmetries of orders {orders:?}");
    }
}

/// Issue 15: a quadruped whose identical legs are directed (knee, toe forward) has only its
/// left–right mirror as a global symmetry; a front leg maps onto a hind leg by a translation
/// of the leg. With the parts stage (`intrinsym::parts`) most ordered leg pairs are found, at
/// rest and walking (12 of 12 each measured at this size, 10k vertices; 4 and 8 with session
/// 33's stage, 4 without the stage), as partial symmetries reported after the global ones,
/// and the first symmetry is still the mirror.
#[test]
fn directed_legs_map_onto_each_other_with_the_parts_stage() {
    let mut params = Params::default();
    params.parts.enabled = true;
    // Ordered leg pairs found (acc@0.1 ≥ 0.8), and how many of them are front ↔ hind.
    let legs = |c: &shapes::Creature, d: &intrinsym::Detection| {
        let mut found = 0;
        let mut cross = 0;
        for i in 0..4 {
            for j in (0..4).filter(|&j| j != i) {
                let best = d.symmetries.iter().map(|s| eval::accuracy(&c.mesh, &s.map, &c.translation_truth(i, j), &[0.1])[0]).fold(0.0, f64::max);
                if best >= 0.8 {
                    found += 1;
                    // Legs 0, 1 are the front ones.
                    cross += usize::from((i < 2) != (j < 2));
                }
            }
        }
        (found, cross)
    };
    let rest = shapes::directed_quadruped(5, Pose::Rest, 0.0, 0);
    let (found, cross) = legs(&rest, &detect(&rest.mesh, &params, &mut |_| true).unwrap());
    assert!(found >= 10 && cross >= 6, "at rest: {found} ordered leg pairs found, {cross} of them front ↔ hind");
    let c = shapes::directed_quadruped(5, Pose::Walking, 0.0, 0);
    let d = detect(&c.mesh, &params, &mut |_| true).unwrap();
    let (found, cross) = legs(&c, &d);
    assert!(found >= 10 && cross >= 6, "walking: {found} ordered leg pairs found, {cross} of them front ↔ hind");
    // With 0.5% noise, seed 1: all 12 (10 in session 35, 8 before its protrusion test let the
    // walking paws of one side, 0.3·√area apart, pair; session 36's compositions with the
    // mirror replaced a wrong map of a diagonal pair), and few partial symmetries that map no
    // leg pair right (2: 3 in session 35, 5 before pairs whose map fits no rigid motion near
    // the tips were dropped, a leg onto the head or the tail).
    let noisy = shapes::directed_quadruped(5, Pose::Walking, 0.005, 1);
    let dn = detect(&noisy.mesh, &params, &mut |_| true).unwrap();
    let (found_noisy, cross_noisy) = legs(&noisy, &dn);
    assert!(found_noisy == 12 && cross_noisy == 8, "noisy: {found_noisy} ordered leg pairs found, {cross_noisy} of them front ↔ hind");
    let maps_a_leg_pair = |s: &intrinsym::Symmetry| (0..4).any(|i| (0..4).filter(|&j| j != i).any(|j| eval::accuracy(&noisy.mesh, &s.map, &noisy.translation_truth(i, j), &[0.1])[0] >= 0.8));
    let wrong = dn.symmetries.iter().filter(|s| s.kind == Kind::Partial && !maps_a_leg_pair(s)).count();
    assert!(wrong <= 2, "noisy: {wrong} partial symmetries map no leg pair right");
    let mirror = eval::accuracy(&c.mesh, &d.symmetries[0].map, &mirror_truth(&c), &[0.05])[0];
    assert!(mirror > 0.9 && d.symmetries[0].kind == Kind::Global, "first symmetry: mirror acc {mirror}");
    let first_partial = d.symmetries.iter().position(|s| s.kind == Kind::Partial).expect("partial symmetries");
    assert!(d.symmetries[first_partial..].iter().all(|s| s.kind == Kind::Partial));
    let partial = d.symmetries.iter().filter(|s| s.kind == Kind::Partial).count();
    for s in d.symmetries.iter().filter(|s| s.kind == Kind::Partial) {
        // −1 outside the region, a part of the surface.
        let region: Vec<usize> = (0..s.map.len()).filter(|&v| s.map[v] >= 0).collect();
        assert_eq!(region.len(), s.region_size);
        assert!(region.len() < c.mesh.num_vertices() / 2);
    }
    // The report shows each partial symmetry's region (orange) and image (blue).
    let svg = intrinsym::output::report::svg(&d, "directed", Some(&c.mesh.vertices));
    assert_eq!(svg.matches(" partial: ").count(), partial);
    assert!(svg.contains("rgb(230,120,0)") && svg.contains("rgb(30,90,220)"));
}

/// Issue 15, step 6 of the parts stage (`PartParams::compose`): at 2.5k vertices the directed
/// quadruped at rest has 10 of its 12 ordered leg pairs mapped directly; the left–right
/// mirror carries the found maps to the missing pairs, and all 12 are found, with no partial
/// symmetry that maps no leg pair right.
#[test]
fn the_mirror_carries_leg_maps_to_the_diagonal_pairs() {
    let c = shapes::directed_quadruped(4, Pose::Rest, 0.0, 0);
    let ordered = |compose: bool| {
        let mut params = Params::default();
        params.parts.enabled = true;
        params.parts.compose = compose;
        let d = detect(&c.mesh, &params, &mut |_| true).unwrap();
        let acc = |s: &intrinsym::Symmetry, i: usize, j: usize| eval::accuracy(&c.mesh, &s.map, &c.translation_truth(i, j), &[0.1])[0];
        let found = (0..4).flat_map(|i| (0..4).filter(move |&j| j != i).map(move |j| (i, j))).filter(|&(i, j)| d.symmetries.iter().any(|s| acc(s, i, j) >= 0.8)).count();
        let wrong = d.symmetries.iter().filter(|s| s.kind == Kind::Partial && !(0..4).any(|i| (0..4).filter(|&j| j != i).any(|j| acc(s, i, j) >= 0.8))).count();
        (found, wrong)
    };
    assert_eq!(ordered(false).0, 10, "direct maps only");
    let (found, wrong) = ordered(true);
    assert_eq!((found, wrong), (12, 0), "with the compositions: ordered pairs found, wrong partial symmetries");
}

/// Issue 15, no spurious parts: the parts stage pairs only the ends of protrusions
/// (`PartParams::max_fill`), so on a three-axis ellipsoid, whose long and middle ends agree in
/// growth profile near their tips, it adds no partial symmetry (3 at this size, 10k vertices,
/// with a part's reach lowered to 1.75 tip radii and no protrusion test).
#[test]
fn the_parts_stage_finds_no_parts_on_an_ellipsoid() {
    let mesh = shapes::ellipsoid(5, [1.0, 0.75, 0.5]);
    let mut params = Params::default();
    params.parts.enabled = true;
    let d = detect(&mesh, &params, &mut |_| true).unwrap();
    let partial: Vec<usize> = d.symmetries.iter().filter(|s| s.kind == Kind::Partial).map(|s| s.region_size).collect();
    assert!(partial.is_empty(), "partial symmetries of {partial:?} vertices");
}

/// The parts stage's maps have a budget of their own (`Params::max_symmetries`): global
/// stages that fill the cap do not crowd them out (on the noisy directed quadruped at 10k
/// vertices, noise seed 7, one search found 32 maps and none of the parts stage's 4 was
/// reported: 4 → 11 of 12 ordered leg pairs with the budget).
#[test]
fn global_maps_that_fill_the_cap_leave_the_parts_their_own() {
    let c = shapes::directed_quadruped(4, Pose::Rest, 0.0, 0);
    let mut params = Params::default();
    params.parts.enabled = true;
    params.max_symmetries = 1;
    let d = detect(&c.mesh, &params, &mut |_| true).unwrap();
    let global = d.symmetries.iter().filter(|s| s.kind == Kind::Global).count();
    let partial = d.symmetries.iter().filter(|s| s.kind == Kind::Partial).count();
    assert!(global <= 1, "{global} global symmetries reported with a cap of 1");
    assert_eq!(partial, 1, "the parts stage's maps, capped at 1 of their own");
    params.max_symmetries = 32;
    let all = detect(&c.mesh, &params, &mut |_| true).unwrap();
    assert!(all.symmetries.iter().filter(|s| s.kind == Kind::Partial).count() >= 4);
}

/// Issue 15, no spurious parts: on the lopsided blob, whose limbs differ in length and
/// girth, the parts stage adds no partial symmetry to those the global stages report. Its
/// limbs of radius 0.3 and 0.22 agreed in growth profile (cumulative areas within 25%) and
/// were paired at both sizes (one map at 2.5k vertices, two at 10k) until the girth test
/// (`PartParams::girth_tolerance`: the rings' areas, mean ratio 0.68–0.80 here against
/// 0.86–1.00 for the repeated legs and spikes of `bench/parts.sh`).
#[test]
fn the_parts_stage_finds_no_parts_on_the_lopsided_blob() {
    for level in [4, 5] {
        let c = shapes::lopsided(level);
        let partial = |parts: bool| {
            let mut params = Params::default();
            params.parts.enabled = parts;
            let d = detect(&c.mesh, &params, &mut |_| true).unwrap();
            d.symmetries.iter().filter(|s| s.kind == Kind::Partial).map(|s| s.region_size).collect::<Vec<usize>>()
        };
        let (with, without) = (partial(true), partial(false));
        assert_eq!(with, without, "level {level}: partial symmetries (region sizes) with the parts stage and without it");
    }
}

/// The swap of two congruent components, one of them detected on a coarse mesh (the
/// hierarchy, forced by a low `hierarchy_vertices`: the shoe of 10k vertices is, its partner of
/// 2.5k is not): found first, and judged with the components' curvature, carried from each
/// component's own detection (measured: acc@0.035 0.98, curvature change 0.13).
#[test]
fn congruent_components_on_the_hierarchy_are_swapped() {
    let (mesh, truth) = shoes(true);
    let mut params = Params::default();
    params.hierarchy_vertices = 1000;
    let d = detect(&mesh, &params, &mut |_| true).unwrap();
    assert!(d.timings.hierarchy > 0.0, "one shoe on the hierarchy");
    let s = &d.symmetries[0];
    assert_eq!(s.components, [0, 1], "{:?}", d.symmetries.iter().map(|s| (s.components, s.verdict)).collect::<Vec<_>>());
    assert!(s.verdict.reverses(), "{:?}", s.verdict);
    let acc = eval::accuracy(&mesh, &s.map, &truth, &[0.035])[0];
    assert!(acc > 0.95, "swap acc {acc}");
    assert!(s.verdict.curvature > 0.0 && s.verdict.curvature < 0.25, "{:?}", s.verdict);
}

/// Parameters of one search from `seed` (no restarts).
fn one_search(seed: u64) -> Params {
    let mut p = Params::default();
    p.seed = seed;
    p.restarts = 0;
    p
}

/// Restarts pool the searches (`Params::restarts`): with every restart forced, the first
/// reported symmetry is the strongest first symmetry of the single searches from the same
/// seeds, and the pool reports each symmetry once.
#[test]
fn restarts_pool_the_searches_and_the_judge_picks() {
    let c = shapes::quadruped(4, Pose::Walking, 0.002, 1);
    // Without the winner's further passes (`MapParams::winner_polish`), which would polish
    // each single search's strongest map and the pool's from other anchors.
    let unpolished = |seed: u64| {
        let mut p = one_search(seed);
        p.maps.winner_polish = 0;
        p
    };
    let singles: Vec<f64> = (1..4).map(|s| detect(&c.mesh, &unpolished(s), &mut |_| true).unwrap().symmetries[0].verdict.score).collect();
    let mut pooled = unpolished(1);
    pooled.restarts = 2;
    pooled.restart_below = f64::INFINITY;
    let d = detect(&c.mesh, &pooled, &mut |_| true).unwrap();
    let strongest = singles.iter().copied().fold(0.0, f64::max);
    // (On this shape a later search finds the stronger version: the pool is exercised.)
    assert!(singles[0] < strongest, "{singles:?}");
    assert!((d.symmetries[0].verdict.score - strongest).abs() < 1e-12, "pooled first {} against the searches' {singles:?}", d.symmetries[0].verdict.score);
    // No symmetry twice: no two reported maps of one orientation type agree on most vertices.
    let n = c.mesh.num_vertices();
    for (i, a) in d.symmetries.iter().enumerate() {
        for b in &d.symmetries[..i] {
            if a.verdict.reverses() == b.verdict.reverses() {
                let same = (0..n).filter(|&v| a.map[v] >= 0 && a.map[v] == b.map[v]).count();
                assert!(same < n * 4 / 5, "symmetries {i} and another map {same} of {n} vertices alike");
            }
        }
    }
    // A search that finds a symmetry the judge trusts ends the searching: the default
    // threshold on this shape (first score from seed 0 above it) gives the single search's
    // result.
    let single = detect(&c.mesh, &one_search(0), &mut |_| true).unwrap();
    assert!(single.symmetries[0].verdict.score >= Params::default().restart_below, "{}", single.symmetries[0].verdict.score);
    let default = detect(&c.mesh, &Params::default(), &mut |_| true).unwrap();
    assert_eq!(default.symmetries[0].map, single.symmetries[0].map);
}

/// Progress moves on through the restarts and never goes back, and cancelling inside a later
/// search stops the detection.
#[test]
fn restarts_report_progress_and_can_be_cancelled() {
    let c = shapes::quadruped(3, Pose::Walking, 0.0, 0);
    let mut p = one_search(0);
    p.restarts = 2;
    p.restart_below = f64::INFINITY;
    let mut calls = Vec::new();
    detect(&c.mesh, &p, &mut |f| {
        calls.push(f);
        true
    })
    .unwrap();
    assert!(calls.windows(2).all(|w| w[1] >= w[0]), "progress went back");
    assert_eq!(calls.last(), Some(&1.0));
    assert!(calls.iter().filter(|&&f| f > 0.9 && f < 0.99).count() >= 4, "the later searches report: {:?}", &calls[calls.len().saturating_sub(12)..]);
    let e = detect(&c.mesh, &p, &mut |f| f < 0.92).unwrap_err();
    assert!(matches!(e, Error::Cancelled { stage } if stage != "eigenbasis" && stage != "report"), "{e}");
}

/// A symmetry far weaker than the strongest is not reported (`Params::min_score_ratio`): the
/// report is the full one with exactly the maps scoring below the ratio of the first left out,
/// in the same order. The ratio is taken half-way between the weakest map's share of the
/// strongest score and 1, so that the weakest is left out. (The generated lopsided blob at 642
/// vertices reports four maps when nothing is left out, scored 0.10–0.19; a fifth, scored
/// 0.31, was a rotation partly the identity, left out by `Params::max_fixed_preserving`.)
#[test]
fn weak_symmetries_are_left_out() {
    let c = shapes::lopsided(3);
    let mut every = Params::default();
    every.min_score_ratio = 0.0;
    let all = detect(&c.mesh, &every, &mut |_| true).unwrap();
    let scores: Vec<f64> = all.symmetries.iter().map(|s| s.verdict.score).collect();
    let top = scores[0];
    let weakest = scores.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(scores.len() >= 2 && weakest < 0.9 * top, "scores {scores:?}");
    let ratio = 0.5 * (1.0 + weakest / top);
    let mut strict = Params::default();
    strict.min_score_ratio = ratio;
    let kept = detect(&c.mesh, &strict, &mut |_| true).unwrap();
    let strong: Vec<&Vec<i64>> = all.symmetries.iter().filter(|s| s.verdict.score >= ratio * top).map(|s| &s.map).collect();
    assert!(strong.len() < all.symmetries.len(), "scores {scores:?}");
    assert_eq!(kept.symmetries.iter().map(|s| &s.map).collect::<Vec<_>>(), strong);
}

/// The further polish (`MapParams::final_polish`) spends its passes on each search's
/// `final_polish_maps` strongest symmetries only: with one search, every other reported map is
/// one reported without it, the strongest map keeps its type and changes (the passes ran), and
/// it stays as accurate (posed quadrupeds with 0.5% noise, four noise seeds: acc@0.05
/// 0.957–0.984 with the eight further passes, 0.963–0.984 without, a change of −0.005 to
/// +0.007 on these generated mirrors; on the shared meshes they gain, docs/accuracy.md
/// "Sessions 24, 25 and 33").
#[test]
fn further_polish_refines_only_the_strongest_symmetries() {
    let mut changed = 0;
    for seed in 0..4 {
        let c = shapes::quadruped(4, Pose::Walking, 0.005, seed);
        let mut without = one_search(0);
        without.maps.final_polish = 0;
        without.maps.winner_polish = 0;
        let a = detect(&c.mesh, &without, &mut |_| true).unwrap();
        for count in [1, 2] {
            let mut with = one_search(0);
            with.maps.final_polish_maps = count;
            with.maps.winner_polish = 0;
            let b = detect(&c.mesh, &with, &mut |_| true).unwrap();
            assert_eq!(a.symmetries.len(), b.symmetries.len(), "seed {seed}, {count} polished");
            // The `count` strongest global maps are the report's first here (no partial map
            // outscores them three times over, `Params::global_preference`).
            assert!(a.symmetries.iter().take(count).all(|s| s.kind == Kind::Global), "seed {seed}");
            for x in &a.symmetries[count.min(a.symmetries.len())..] {
                assert!(b.symmetries.iter().any(|y| y.map == x.map), "seed {seed}, {count} polished: a map other than the strongest changed");
            }
            let (s, t) = (&a.symmetries[0], &b.symmetries[0]);
            assert_eq!((s.order, s.verdict.reverses()), (t.order, t.verdict.reverses()), "seed {seed}");
            changed += usize::from(s.map != t.map);
            let acc = |d: &intrinsym::Detection| eval::accuracy(&c.mesh, &d.symmetries[0].map, &mirror_truth(&c), &[0.05])[0];
            let (before, after) = (acc(&a), acc(&b));
            assert!(after >= 0.9 && after >= before - 0.01, "seed {seed}, {count} polished: acc@0.05 {before} -> {after}");
        }
    }
    assert!(changed >= 4, "the further passes changed the strongest map in {changed} of 8 detections");
}

/// The strongest symmetry over all searches gets `MapParams::winner_polish` further
/// (settling) passes once the searches are pooled: every other reported map is one reported
/// without them, the strongest keeps its type and stays accurate. Measured on posed
/// quadrupeds with 0.5% noise, four noise seeds: acc@0.05 0.988–0.995 without them,
/// 0.973–0.982 with them (acc@0.02 0.927–0.957 → 0.896–0.923). Heavy noise on a coarse mesh
/// is where the settling passes, which do not smooth, lose a little: each vertex is placed
/// by its own noisy geodesics. On shared/data they gain, and on its noisy copies they hold
/// (docs/accuracy.md, "Session 42").
#[test]
fn winner_polish_refines_only_the_strongest_symmetry() {
    let mut changed = 0;
    for seed in 0..4 {
        let c = shapes::quadruped(4, Pose::Walking, 0.005, seed);
        let mut without = Params::default();
        without.maps.winner_polish = 0;
        let a = detect(&c.mesh, &without, &mut |_| true).unwrap();
        let b = detect(&c.mesh, &Params::default(), &mut |_| true).unwrap();
        assert_eq!(a.symmetries.len(), b.symmetries.len(), "seed {seed}");
        for x in &a.symmetries[1..] {
            assert!(b.symmetries.iter().any(|y| y.map == x.map), "seed {seed}: a map other than the strongest changed");
        }
        let (s, t) = (&a.symmetries[0], &b.symmetries[0]);
        assert_eq!((s.kind, s.order, s.verdict.reverses()), (t.kind, t.order, t.verdict.reverses()), "seed {seed}");
        changed += usize::from(s.map != t.map);
        let acc = |d: &intrinsym::Detection| eval::accuracy(&c.mesh, &d.symmetries[0].map, &mirror_truth(&c), &[0.05])[0];
        let (before, after) = (acc(&a), acc(&b));
        assert!(after >= 0.95 && after >= before - 0.025, "seed {seed}: acc@0.05 {before} -> {after}");
    }
    assert!(changed >= 1, "the winner's passes changed the strongest map in none of 4 detections");
}

/// A scan's holes on one side only (three of radius 0.08·√area on a posed quadruped, 2.5k
/// vertices) break the symmetry of the Laplacian's eigenfunctions everywhere (Neumann rims);
/// capped before detection (`intrinsym::mesh::holes`), the mirror is found on what is left,
/// every vertex mapped, none into a hole.
#[test]
fn holes_on_one_side_do_not_hide_the_mirror() {
    let c = shapes::quadruped(4, Pose::Walking, 0.0, 0);
    let p = &c.mesh.vertices;
    let n = p.len();
    let d = |v: usize| [0, 1, 2].map(|k| p[v][k] - p[c.mirror[v] as usize][k]);
    let len = |a: [f64; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    let far = (0..n).max_by(|&a, &b| len(d(a)).total_cmp(&len(d(b)))).unwrap();
    let normal = d(far);
    let side = |v: usize| d(v).iter().zip(&normal).map(|(a, b)| a * b).sum::<f64>();
    let candidates: Vec<usize> = (0..n).filter(|&v| side(v) > 0.3 * len(normal) * len(normal)).collect();
    // Three centres spread over that side (farthest points of each other).
    let dist = |a: usize, b: usize| len([0, 1, 2].map(|k| p[a][k] - p[b][k]));
    let mut centres = vec![candidates[0]];
    for _ in 0..2 {
        let next = *candidates.iter().max_by(|&&a, &&b| {
            let da = centres.iter().map(|&h| dist(a, h)).fold(f64::INFINITY, f64::min);
            let db = centres.iter().map(|&h| dist(b, h)).fold(f64::INFINITY, f64::min);
            da.total_cmp(&db)
        }).unwrap();
        centres.push(next);
    }
    let radius = 0.08 * c.mesh.area().sqrt();
    let near = |v: u32| centres.iter().any(|&h| dist(v as usize, h) < radius);
    let kept: Vec<[u32; 3]> = c.mesh.triangles.iter().filter(|t| !t.iter().any(|&v| near(v))).copied().collect();
    let holed = Mesh::new(p.clone(), kept, &MeshParams::default()).unwrap();
    assert!(holed.info.isolated_vertices > 0);
    let present: Vec<bool> = {
        let mut used = vec![false; n];
        holed.input_index.iter().for_each(|&i| used[i as usize] = true);
        used
    };
    // `eval::accuracy` takes the holed mesh's own vertex indices; results are in the input's.
    let mut local = vec![usize::MAX; n];
    holed.input_index.iter().enumerate().for_each(|(v, &i)| local[i as usize] = v);
    let truth: Vec<(usize, Vec<usize>)> = (0..n).filter(|&v| present[v] && present[c.mirror[v] as usize]).map(|v| (local[v], vec![local[c.mirror[v] as usize]])).collect();
    let score = |max_hole: f64| {
        let mut params = Params::default();
        params.max_hole = max_hole;
        let d = detect(&holed, &params, &mut |_| true).unwrap();
        let first = d.symmetries.first().map_or(0.0, |s| {
            let pred: Vec<i64> = holed.input_index.iter().map(|&i| s.map[i as usize]).map(|w| if w < 0 { -1 } else { local[w as usize] as i64 }).collect();
            eval::accuracy(&holed, &pred, &truth, &[0.05])[0]
        });
        (d, first)
    };
    let (closed, first) = score(intrinsym::mesh::holes::MAX_LOOP);
    let (_, open) = score(0.0);
    println!("holes on one side: first symmetry acc@0.05 {first:.3} with the holes capped, {open:.3} without");
    assert!(closed.mesh.closed_holes >= 3, "{:?}", closed.mesh);
    assert!(first >= 0.85, "acc@0.05 {first:.3} (without capping {open:.3})");
    let s = &closed.symmetries[0];
    assert_eq!((s.kind, s.order), (Kind::Global, 2));
    assert_eq!(s.map.len(), n);
    assert!((0..n).all(|v| (s.map[v] >= 0) == present[v]), "mapped exactly the vertices left");
    assert!(s.map.iter().filter(|&&w| w >= 0).all(|&w| present[w as usize]), "an image in a hole");
}

/// Each symmetry is reported once: no two reported maps of one kind and orientation type send
/// 80% of the vertices within 0.05·√area (the scorer's radius) of each other. A search merges
/// the versions of a symmetry again after its further passes, which can turn the second
/// strongest map, a partly wrong version of the first, into another version of it (FAUST's
/// tr_reg_011 reported its mirror twice, 0.94 and 0.95 acc@0.05, before; docs/accuracy.md,
/// "Session 43"). The generated shapes here did not show such a pair before that either:
/// the test guards the invariant on shapes with several symmetries, noisy and clean.
#[test]
fn no_symmetry_is_reported_twice() {
    let cases = [
        ("walking, 0.5% noise", shapes::quadruped(4, Pose::Walking, 0.005, 1)),
        ("directed at rest, 0.5% noise", shapes::directed_quadruped(4, Pose::Rest, 0.005, 2)),
        ("star", shapes::star(5, 4)),
    ];
    for (name, c) in &cases {
        let d = run(c);
        let n = c.mesh.num_vertices();
        for (i, a) in d.symmetries.iter().enumerate() {
            for (j, b) in d.symmetries[..i].iter().enumerate() {
                if a.kind != b.kind || a.verdict.reverses() != b.verdict.reverses() {
                    continue;
                }
                let b_as_truth: Vec<(usize, Vec<usize>)> = (0..n).filter(|&v| b.map[v] >= 0).map(|v| (v, vec![b.map[v] as usize])).collect();
                let alike = eval::accuracy(&c.mesh, &a.map, &b_as_truth, &[0.05])[0];
                assert!(alike < 0.8, "{name}: symmetries {j} and {i} agree on {alike:.3} of the vertices");
            }
        }
    }
}
