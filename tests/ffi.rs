//! The C ABI called from Rust (as rav1e's capi tests do): handles, statuses, borrowed views.

use std::ffi::CStr;
use std::ptr;

use intrinsym::ffi::*;
use intrinsym::shapes::{self, Pose};

fn last_error() -> String {
    let mut buf = [0 as std::ffi::c_char; 256];
    let mut len = 0usize;
    assert_eq!(unsafe { sym_last_error(buf.as_mut_ptr(), buf.len(), &mut len) }, sym_status::SYM_STATUS_OK);
    unsafe { CStr::from_ptr(buf.as_ptr()) }.to_string_lossy().into_owned()
}

/// The rest-pose quadruped at `level` as the C API's flat arrays.
fn quadruped_arrays(level: u32) -> (shapes::Creature, Vec<f64>, Vec<u32>) {
    let c = shapes::quadruped(level, Pose::Rest, 0.0, 0);
    let v: Vec<f64> = c.mesh.vertices.iter().flatten().copied().collect();
    let t: Vec<u32> = c.mesh.triangles.iter().flatten().copied().collect();
    (c, v, t)
}

#[test]
fn detect_get_map_free() {
    let (c, v, t) = quadruped_arrays(3);
    let p = sym_params_new();
    assert_eq!(sym_params_set_samples(p, 48), sym_status::SYM_STATUS_OK);
    let mut r: *mut sym_result = ptr::null_mut();
    let st = unsafe { sym_detect(v.as_ptr(), c.mesh.num_vertices(), t.as_ptr(), c.mesh.num_triangles(), p, None, ptr::null_mut(), &mut r) };
    assert_eq!(st, sym_status::SYM_STATUS_OK, "{}", last_error());
    assert!(sym_count(r) >= 1);
    assert_eq!(sym_vertex_count(r), c.mesh.num_vertices());
    let mut s: sym_symmetry = unsafe { std::mem::zeroed() };
    s.struct_size = std::mem::size_of::<sym_symmetry>();
    assert_eq!(unsafe { sym_get_map(r, 0, &mut s) }, sym_status::SYM_STATUS_OK);
    let map = unsafe { std::slice::from_raw_parts(s.map, s.num_vertices) };
    let exact = (0..map.len()).filter(|&i| map[i] == c.mirror[i] as i64).count();
    assert!(exact * 100 >= 95 * map.len(), "{exact} of {}", map.len());
    let fmap = unsafe { std::slice::from_raw_parts(s.fmap, s.fmap_size * s.fmap_size) };
    assert!(fmap.iter().all(|x| x.is_finite()));
    sym_free(r);
    sym_free(r); // double free is a no-op
    assert_eq!(sym_count(r), 0, "a freed handle is refused");
    sym_params_free(p);
}

/// The proxy through the C API: a 2.5k quadruped with a 1,000-vertex proxy still gets a map
/// of every vertex, mostly onto its mirror image; an out-of-range size is refused.
#[test]
fn proxy_size_is_a_parameter() {
    let (c, v, t) = quadruped_arrays(4);
    let p = sym_params_new();
    assert_eq!(sym_params_set_proxy_vertices(p, 999), sym_status::SYM_STATUS_INVALID_ARGUMENT);
    assert_eq!(sym_params_set_proxy_vertices(p, 1000), sym_status::SYM_STATUS_OK);
    let mut r: *mut sym_result = ptr::null_mut();
    let st = unsafe { sym_detect(v.as_ptr(), c.mesh.num_vertices(), t.as_ptr(), c.mesh.num_triangles(), p, None, ptr::null_mut(), &mut r) };
    assert_eq!(st, sym_status::SYM_STATUS_OK, "{}", last_error());
    let mut s: sym_symmetry = unsafe { std::mem::zeroed() };
    s.struct_size = std::mem::size_of::<sym_symmetry>();
    assert_eq!(unsafe { sym_get_map(r, 0, &mut s) }, sym_status::SYM_STATUS_OK);
    let map = unsafe { std::slice::from_raw_parts(s.map, s.num_vertices) };
    assert!(map.iter().all(|&w| w >= 0 && (w as usize) < map.len()));
    // Lifted from the proxy: within 0.05·√area of the mirror image.
    let truth: Vec<(usize, Vec<usize>)> = (0..map.len()).map(|v| (v, vec![c.mirror[v] as usize])).collect();
    let acc = intrinsym::eval::accuracy(&c.mesh, map, &truth, &[0.05])[0];
    assert!(acc >= 0.95, "acc@0.05 {acc}");
    sym_free(r);
    sym_params_free(p);
}

/// The curvature weight through the C API reaches the detection: with 0 the scores are those
/// of the Rust detection without the curvature term (the judge's curvature factor is 1), not
/// the default's; a negative or NaN weight is refused and changes nothing.
#[test]
fn curvature_weight_is_a_parameter() {
    let (c, v, t) = quadruped_arrays(3);
    let p = sym_params_new();
    assert_eq!(sym_params_set_curvature_weight(p, -0.5), sym_status::SYM_STATUS_INVALID_ARGUMENT);
    assert!(last_error().contains("sym_params_set_curvature_weight"), "{}", last_error());
    assert_eq!(sym_params_set_curvature_weight(p, f64::NAN), sym_status::SYM_STATUS_INVALID_ARGUMENT);
    assert_eq!(sym_params_set_curvature_weight(p, 0.0), sym_status::SYM_STATUS_OK);
    let mut r: *mut sym_result = ptr::null_mut();
    let st = unsafe { sym_detect(v.as_ptr(), c.mesh.num_vertices(), t.as_ptr(), c.mesh.num_triangles(), p, None, ptr::null_mut(), &mut r) };
    assert_eq!(st, sym_status::SYM_STATUS_OK, "{}", last_error());
    let scores: Vec<f64> = (0..sym_count(r))
        .map(|i| {
            let mut s: sym_symmetry = unsafe { std::mem::zeroed() };
            s.struct_size = std::mem::size_of::<sym_symmetry>();
            assert_eq!(unsafe { sym_get_map(r, i, &mut s) }, sym_status::SYM_STATUS_OK);
            s.score
        })
        .collect();
    sym_free(r);
    sym_params_free(p);
    let rust = |weight: f64| {
        let mut params = intrinsym::Params::default();
        params.maps.curvature_weight = weight;
        let d = intrinsym::detect(&c.mesh, &params, &mut |_| true).unwrap();
        d.symmetries.iter().map(|s| s.verdict.score).collect::<Vec<f64>>()
    };
    assert_eq!(scores, rust(0.0));
    assert_ne!(scores, rust(0.03), "the default weight gives the same scores: the test cannot tell");
}

#[test]
fn failures_leave_out_untouched_and_explain() {
    let v = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, f64::NAN, 0.0];
    let t = [0u32, 1, 2];
    let sentinel = 0x1234 as *mut sym_result;
    let mut r = sentinel;
    let st = unsafe { sym_detect(v.as_ptr(), 3, t.as_ptr(), 1, ptr::null(), None, ptr::null_mut(), &mut r) };
    assert_eq!(st, sym_status::SYM_STATUS_INVALID_MESH);
    assert_eq!(r, sentinel);
    assert!(last_error().contains("vertex 2 has a NaN"), "{}", last_error());
    let st = unsafe { sym_detect(ptr::null(), 3, t.as_ptr(), 1, ptr::null(), None, ptr::null_mut(), &mut r) };
    assert_eq!(st, sym_status::SYM_STATUS_NULL_PARAMETER);
    assert!(last_error().contains("vertices"));
    let msg = unsafe { CStr::from_ptr(sym_status_str(sym_status::SYM_STATUS_CANCELLED as i32)) };
    assert!(msg.to_str().unwrap().contains("cancel"));
    let version = unsafe { CStr::from_ptr(sym_version()) };
    assert_eq!(version.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
    assert_eq!(sym_abi_version(), SYM_ABI_VERSION);
}

unsafe extern "C" fn stop_at_half(fraction: f32, user: *mut std::ffi::c_void) -> std::ffi::c_int {
    unsafe { *(user as *mut f32) = fraction };
    (fraction < 0.5) as std::ffi::c_int
}

#[test]
fn progress_callback_cancels() {
    let (c, v, t) = quadruped_arrays(3);
    let mut seen = 0.0f32;
    let mut r: *mut sym_result = ptr::null_mut();
    let st = unsafe {
        sym_detect(v.as_ptr(), c.mesh.num_vertices(), t.as_ptr(), c.mesh.num_triangles(), ptr::null(), Some(stop_at_half), (&mut seen as *mut f32).cast(), &mut r)
    };
    assert_eq!(st, sym_status::SYM_STATUS_CANCELLED);
    assert!(r.is_null());
    assert!(seen >= 0.5, "last fraction {seen}");
}
