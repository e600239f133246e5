//! Opaque handles and the entry points.
//!
//! Handles are not addresses: each is a serial number never reused, tagged with its type, and
//! looked up in that type's registry. A value that is not a live handle of the expected type
//! (freed, of the other type, or made up) is refused with `SYM_STATUS_INVALID_ARGUMENT` and a
//! message that says which, instead of being dereferenced; freeing it is a no-op.

use std::collections::BTreeMap;
use std::ffi::{c_char, c_int, c_void};
use std::sync::Mutex;

use super::boundary::{guard, guard_value, last_error, set_error};
use super::status::{from_error, sym_status};
use crate::detect::{detect, Detection, Kind, Params};
use crate::mesh::{ComponentPolicy, Mesh, MeshParams};

/// Detection parameters (opaque). Create with [`sym_params_new`], free with [`sym_params_free`].
pub struct sym_params {
    params: Params,
    mesh: MeshParams,
}

/// A detection result (opaque). Produced by [`sym_detect`], freed by [`sym_free`].
pub struct sym_result {
    det: Detection,
    /// Per symmetry: row-major functional map and flattened support pairs.
    fmaps: Vec<Vec<f64>>,
    pairs: Vec<Vec<i64>>,
    quality: Vec<f64>,
}

/// Whether a symmetry covers the whole surface.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum sym_kind {
    /// Defined on every vertex.
    SYM_KIND_GLOBAL = 0,
    /// Defined on a region (`map[v] == -1` outside it).
    SYM_KIND_PARTIAL = 1,
}

/// One symmetry, as borrowed views into a [`sym_result`] (valid until [`sym_free`]).
///
/// Set `struct_size = sizeof(sym_symmetry)` before calling [`sym_get_map`]: later versions may
/// append fields, and the library writes only the fields that fit.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sym_symmetry {
    /// Size of this struct as the caller knows it.
    pub struct_size: usize,
    /// Seed correspondence: source vertex (input index).
    pub source: i64,
    /// Seed correspondence: target vertex.
    pub target: i64,
    /// Global or partial.
    pub kind: sym_kind,
    /// 2 for a reflection-like involution, n for a rotation of order n, 0 if undetermined.
    pub order: u32,
    /// Group label.
    pub group: u32,
    /// Vertices in the region.
    pub region_size: usize,
    /// `Σ W|C| / ‖C‖_F`: 0 for a perfect isometry, larger for more complex maps.
    pub complexity: f64,
    /// Mean `|d(x,y) − d(Tx,Ty)|` over sample pairs / biharmonic diameter.
    pub distortion: f64,
    /// Length of `map` and `confidence` (the input vertex count).
    pub num_vertices: usize,
    /// `map[v]` = image of vertex v, or -1 outside the region.
    pub map: *const i64,
    /// Per-vertex confidence in [0, 1].
    pub confidence: *const f64,
    /// Size k_f of the functional map.
    pub fmap_size: usize,
    /// Functional map, k_f × k_f, row-major.
    pub fmap: *const f64,
    /// Number of support correspondences.
    pub num_support_pairs: usize,
    /// Support correspondences as (source, target) pairs: 2 × num_support_pairs values.
    pub support_pairs: *const i64,
    /// The judge's score in [0, 1] that symmetries are ranked by (higher is better; added in
    /// 0.2: written only when `struct_size` covers it).
    pub score: f64,
    /// Fraction of small surface triangles whose orientation the map reverses: near 1 for a
    /// reflection, near 0 for a rotation (added in 0.2).
    pub reversal: f64,
    /// Fraction of the surface where the map is locally the identity (points stay, orientation
    /// kept; added in 0.2).
    pub fixed: f64,
    /// The connected component the map goes from (0 = the largest processed one; added in
    /// 0.4: written only when `struct_size` covers it).
    pub source_component: u32,
    /// The component it goes to: the same for a symmetry of one component, another for a map
    /// between congruent components (the map then sends each onto the other; added in 0.4).
    pub target_component: u32,
}

/// What validating the mesh found and decided (added in 0.3). Set `struct_size =
/// sizeof(sym_mesh_report)` before calling [`sym_get_mesh_report`].
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct sym_mesh_report {
    /// Size of this struct as the caller knows it.
    pub struct_size: usize,
    /// Vertices in the input arrays.
    pub input_vertices: usize,
    /// Triangles in the input arrays.
    pub input_triangles: usize,
    /// Vertices used by no triangle (ignored: map −1, confidence 0).
    pub isolated_vertices: usize,
    /// Connected components of the input.
    pub components: usize,
    /// Vertices of the components that were not processed (smaller than 1% of the largest).
    pub ignored_component_vertices: usize,
    /// Edges shared by more than two triangles (accepted).
    pub non_manifold_edges: usize,
    /// Zero-area triangles (kept).
    pub degenerate_triangles: usize,
    /// Vertices welded to a coincident one (they get its map).
    pub welded_vertices: usize,
    /// Triangles that welding collapsed (dropped).
    pub collapsed_triangles: usize,
    /// Components processed, each on its own (added in 0.4: written only when `struct_size`
    /// covers it).
    pub kept_components: usize,
    /// Triangles repeating an earlier one's three vertices, in either orientation (dropped;
    /// added in 0.7: written only when `struct_size` covers it).
    pub duplicate_triangles: usize,
    /// Holes capped for the detection (boundary loops short against the surface; added in
    /// 0.7: written only when `struct_size` covers it).
    pub closed_holes: usize,
}

/// Progress callback: `fraction` in [0, 1]; return 0 to cancel, nonzero to continue.
pub type sym_progress_fn = Option<unsafe extern "C" fn(fraction: f32, user_data: *mut c_void) -> c_int>;

/// The live handles of one type. A handle is not an address but a tag: a serial number
/// (never reused in the process's life) shifted left by two, plus the type's tag in the low
/// bits. So a handle of one type is never taken for the other (issue 16, item 8), and a freed
/// handle never comes back to life when the allocator reuses its memory (item 9). The values
/// live in boxes, which do not move: the views `sym_get_map` lends stay valid until the free.
struct Registry<T> {
    next: usize,
    live: BTreeMap<usize, Box<T>>,
}

const PARAMS_TAG: usize = 1;
const RESULT_TAG: usize = 2;

static PARAMS: Mutex<Registry<sym_params>> = Mutex::new(Registry { next: 1, live: BTreeMap::new() });
static RESULTS: Mutex<Registry<sym_result>> = Mutex::new(Registry { next: 1, live: BTreeMap::new() });

impl<T> Registry<T> {
    fn lock(m: &Mutex<Self>) -> std::sync::MutexGuard<'_, Self> {
        m.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Stores `value`; its handle.
    fn insert(m: &Mutex<Self>, tag: usize, value: T) -> usize {
        let mut r = Self::lock(m);
        let handle = (r.next << 2) | tag;
        r.next += 1;
        r.live.insert(handle, Box::new(value));
        handle
    }

    /// The value of a live handle. The box's content does not move while it is registered.
    fn get(m: &Mutex<Self>, handle: usize) -> Option<*mut T> {
        Self::lock(m).live.get_mut(&handle).map(|b| &mut **b as *mut T)
    }

    fn remove(m: &Mutex<Self>, handle: usize) -> Option<Box<T>> {
        Self::lock(m).live.remove(&handle)
    }
}

/// What a pointer that is not a live handle of the expected type is, for the message.
fn describe(p: usize, expected: &str) -> String {
    if p & 3 == PARAMS_TAG && Registry::get(&PARAMS, p).is_some() {
        format!("a sym_params handle where a {expected} is expected")
    } else if p & 3 == RESULT_TAG && Registry::get(&RESULTS, p).is_some() {
        format!("a sym_result handle where a {expected} is expected")
    } else {
        format!("not a live {expected} (freed, or not from this library)")
    }
}

type Fail = (sym_status, String);

/// Counts above this are refused as absurd: `3 ×` that many 8-byte values would not fit in the
/// address space, so no caller can hold such arrays.
const ABSURD_COUNT: usize = (isize::MAX as usize) / 32;

/// The `struct_size` the caller declared in `*out`, at least `min` bytes (the struct's first
/// version). Every versioned out-struct (`sym_symmetry`, `sym_mesh_report`) is `#[repr(C)]`
/// with `struct_size: usize` first, so later versions may append fields.
///
/// # Safety
/// `out` is non-NULL and its first `usize` initialised.
unsafe fn declared_size<T>(out: *mut T, name: &str, min: usize) -> Result<usize, Fail> {
    // SAFETY: `struct_size` is the first field (see above) and initialised by contract.
    let size = unsafe { out.cast::<usize>().read() };
    if size < min {
        return Err(invalid(format!("out->struct_size is {size}, at least {min} (sizeof({name})) expected")));
    }
    Ok(size)
}

/// Copies the first `min(sizeof(T), caller_size)` bytes of `value` to `out`: the fields the
/// caller's version of the struct has.
///
/// # Safety
/// `out` has `caller_size` writable bytes.
unsafe fn write_versioned<T>(out: *mut T, value: &T, caller_size: usize) {
    let n = std::mem::size_of::<T>().min(caller_size);
    // SAFETY: n ≤ caller_size writable bytes at `out`; `value` is a whole `T`.
    unsafe { std::ptr::copy_nonoverlapping((value as *const T).cast::<u8>(), out.cast::<u8>(), n) };
}

fn null(name: &str) -> Fail {
    (sym_status::SYM_STATUS_NULL_PARAMETER, format!("{name} is NULL"))
}

fn invalid(message: impl Into<String>) -> Fail {
    (sym_status::SYM_STATUS_INVALID_ARGUMENT, message.into())
}

/// Checks a params pointer: NULL, unknown or freed pointers are errors.
fn params_ref<'a>(p: *const sym_params, name: &str) -> Result<&'a sym_params, Fail> {
    if p.is_null() {
        return Err(null(name));
    }
    let value = Registry::get(&PARAMS, p as usize).ok_or_else(|| invalid(format!("{name} is {}", describe(p as usize, "sym_params"))))?;
    // SAFETY: a registered box, freed only by sym_params_free; the caller does not free a
    // handle while another call uses it (documented).
    Ok(unsafe { &*value })
}

fn params_mut<'a>(p: *mut sym_params) -> Result<&'a mut sym_params, Fail> {
    params_ref(p, "params")?;
    let value = Registry::get(&PARAMS, p as usize).ok_or_else(|| invalid("params is not a live sym_params"))?;
    // SAFETY: as in params_ref; the caller must not share the handle across threads while
    // setting (documented).
    Ok(unsafe { &mut *value })
}

fn result_ref<'a>(r: *const sym_result) -> Result<&'a sym_result, Fail> {
    if r.is_null() {
        return Err(null("result"));
    }
    let value = Registry::get(&RESULTS, r as usize).ok_or_else(|| invalid(format!("result is {}", describe(r as usize, "sym_result"))))?;
    // SAFETY: a registered box, freed only by sym_free; the caller does not free a handle
    // while another call uses it (documented).
    Ok(unsafe { &*value })
}

/// Creates parameters with the defaults (100 eigenpairs, 64 samples, seed 0, automatic groups).
/// Returns NULL only if allocation fails. Free with [`sym_params_free`].
#[no_mangle]
pub extern "C" fn sym_params_new() -> *mut sym_params {
    guard_value(std::ptr::null_mut(), || {
        Registry::insert(&PARAMS, PARAMS_TAG, sym_params { params: Params::default(), mesh: MeshParams::default() }) as *mut sym_params
    })
}

/// Frees parameters from [`sym_params_new`]. NULL, a handle already freed, or a handle of
/// another type (a `sym_result`) is a no-op: nothing is freed.
#[no_mangle]
pub extern "C" fn sym_params_free(params: *mut sym_params) {
    guard_value((), || drop(Registry::remove(&PARAMS, params as usize)))
}

/// Applies a checked setting to a live params handle.
fn set(params: *mut sym_params, name: &str, range: &str, ok: bool, value: impl std::fmt::Display, apply: impl FnOnce(&mut sym_params)) -> sym_status {
    guard(|| {
        let p = params_mut(params)?;
        if !ok {
            return Err(invalid(format!("{name}: value {value} is out of range ({range})")));
        }
        apply(p);
        Ok(())
    })
}

/// Number of Laplace–Beltrami eigenpairs, 3 to 1000 (default 100). Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_eigenpairs(params: *mut sym_params, value: usize) -> sym_status {
    set(params, "sym_params_set_eigenpairs", "3 to 1000", (3..=1000).contains(&value), value, |p| p.params.eigen.k = value)
}

/// Farthest-point samples, 8 to 1000 (default 64; the paper uses 20–100). Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_samples(params: *mut sym_params, value: usize) -> sym_status {
    set(params, "sym_params_set_samples", "8 to 1000", (8..=1000).contains(&value), value, |p| p.params.samples = value)
}

/// Random seed (default 0): results are deterministic for a seed. Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_seed(params: *mut sym_params, value: u64) -> sym_status {
    set(params, "sym_params_set_seed", "any", true, value, |p| p.params.seed = value)
}

/// Further searches from other first samples (seeds `seed + 1`, `seed + 2`, …) while the
/// strongest symmetry found scores below 0.4; their symmetries are pooled and the judge picks.
/// 0 to 8 (default 2; 0: one search, fastest). Returns `SYM_STATUS_INVALID_ARGUMENT`
/// (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_restarts(params: *mut sym_params, value: usize) -> sym_status {
    set(params, "sym_params_set_restarts", "0 to 8", value <= 8, value, |p| p.params.restarts = value)
}

/// Symmetries whose judge's score is below this fraction of the strongest one's are not
/// reported, in [0, 1] (default 0.2; 0: every symmetry found, the weak ones included); above
/// 0, neither is a global map that agrees with a stronger reported one of its orientation
/// type on 30% of the probes and fixes at least half as many vertices (a weaker version of
/// it). Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_min_score_ratio(params: *mut sym_params, value: f64) -> sym_status {
    set(params, "sym_params_set_min_score_ratio", "0 to 1", (0.0..=1.0).contains(&value), value, |p| p.params.min_score_ratio = value)
}

/// A partial symmetry (a map of part of the shape) is reported before a global one only if its
/// judge's score is more than this many times higher, a finite number ≥ 1 (default 3; 1: by
/// score alone). Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_global_preference(params: *mut sym_params, value: f64) -> sym_status {
    set(params, "sym_params_set_global_preference", "a finite number ≥ 1", value.is_finite() && value >= 1.0, value, |p| p.params.global_preference = value)
}

/// Weight of the polish's one extrinsic cue, band-limited mean curvature, which also ranks
/// the symmetries and drops maps that change it far more than a true symmetry does; a finite
/// number ≥ 0 (default 0.03; 0: purely intrinsic maps and ranking, for a shape that bends
/// without stretching; the cue fades by itself on noisy meshes; added in 0.7.4). Returns
/// `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_curvature_weight(params: *mut sym_params, value: f64) -> sym_status {
    set(params, "sym_params_set_curvature_weight", "a finite number ≥ 0", value.is_finite() && value >= 0.0, value, |p| p.params.maps.curvature_weight = value)
}

/// Good voters: WKS distance below this quantile of sample pairs, in (0, 1] (default 0.2). Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_wks_quantile(params: *mut sym_params, value: f64) -> sym_status {
    set(params, "sym_params_set_wks_quantile", "greater than 0, at most 1", value > 0.0 && value <= 1.0, value, |p| p.params.voting.wks_quantile = value)
}

/// Voting tolerance ε as a fraction of the biharmonic diameter, in (0, 0.5] (default 0.04). Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_voting_eps(params: *mut sym_params, value: f64) -> sym_status {
    set(params, "sym_params_set_voting_eps", "greater than 0, at most 0.5", value > 0.0 && value <= 0.5, value, |p| p.params.voting.eps = value)
}

/// Region tolerance (mean distance mismatch / diameter), in (0, 0.5] (default 0.03). Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_accept(params: *mut sym_params, value: f64) -> sym_status {
    set(params, "sym_params_set_accept", "greater than 0, at most 0.5", value > 0.0 && value <= 0.5, value, |p| p.params.maps.accept = value)
}

/// Number of symmetry groups, 0 = automatic (default), at most 64. Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_groups(params: *mut sym_params, value: usize) -> sym_status {
    set(params, "sym_params_set_groups", "0 = automatic, or 1 to 64", value <= 64, value, |p| p.params.groups = if value == 0 { None } else { Some(value) })
}

/// Size of the proxy on which a large mesh's maps are made and then lifted to every vertex:
/// meshes of more than 1.5 times this many vertices use one (default 6000); 0 makes the maps
/// on the whole mesh (slower above 9,000 vertices, not more accurate as measured). 0 or
/// 1000–10⁶. Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_proxy_vertices(params: *mut sym_params, value: usize) -> sym_status {
    set(params, "sym_params_set_proxy_vertices", "0 = off, or 1000 to 1000000", value == 0 || (1000..=1_000_000).contains(&value), value, |p| p.params.maps.proxy_vertices = value)
}

/// Nonzero: accept edges shared by more than two triangles (default 1 since 0.3: accept them,
/// with the Laplacian of the tufted cover); 0: refuse them with `SYM_STATUS_INVALID_MESH`.
#[no_mangle]
pub extern "C" fn sym_params_set_allow_non_manifold(params: *mut sym_params, value: c_int) -> sym_status {
    set(params, "sym_params_set_allow_non_manifold", "any", true, value, |p| p.mesh.allow_non_manifold = value != 0)
}

/// Nonzero: weld coincident vertices (default 1: boundary vertices closer than 10⁻⁶ of the
/// bounding-box diagonal are one, as in an STL-style triangle soup or a split seam; a welded
/// vertex gets the map of the vertex it joined); 0: keep them apart (added in 0.3).
#[no_mangle]
pub extern "C" fn sym_params_set_weld(params: *mut sym_params, value: c_int) -> sym_status {
    set(params, "sym_params_set_weld", "any", true, value, |p| p.mesh.weld = value != 0)
}

/// Nonzero: refuse meshes with several connected components (default 0: process each component of at least 1% of the largest one's area, and map congruent components onto each other). Returns `SYM_STATUS_INVALID_ARGUMENT` (settings unchanged) outside the range.
#[no_mangle]
pub extern "C" fn sym_params_set_reject_disconnected(params: *mut sym_params, value: c_int) -> sym_status {
    set(params, "sym_params_set_reject_disconnected", "any", true, value, |p| p.mesh.components = if value != 0 { ComponentPolicy::Reject } else { ComponentPolicy::Each })
}

/// Nonzero: also look for partial symmetries between repeated parts that no global symmetry
/// carries (a front paw onto a hind paw; experimental, default 0; added in 0.5). Each is
/// reported after the global symmetries, `kind` partial, its map −1 outside the two parts.
#[no_mangle]
pub extern "C" fn sym_params_set_parts(params: *mut sym_params, value: c_int) -> sym_status {
    set(params, "sym_params_set_parts", "any", true, value, |p| p.params.parts.enabled = value != 0)
}

/// Detects the intrinsic symmetries of a triangle mesh.
///
/// `vertices`: `3 * num_vertices` doubles, row-major (x, y, z); `triangles`: `3 * num_triangles`
/// 0-based indices. `params` may be NULL (defaults). `progress` may be NULL; it is called with
/// the fraction done and `user_data`, and returning 0 cancels (`SYM_STATUS_CANCELLED`). On
/// success `*out` receives a result to free with [`sym_free`]; on failure `*out` is untouched
/// and [`sym_last_error`] tells why.
///
/// # Safety
/// `vertices` and `triangles` must point to arrays of at least the stated lengths, and
/// `out` to writable memory; the arrays are only read during the call.
#[no_mangle]
pub unsafe extern "C" fn sym_detect(
    vertices: *const f64,
    num_vertices: usize,
    triangles: *const u32,
    num_triangles: usize,
    params: *const sym_params,
    progress: sym_progress_fn,
    user_data: *mut c_void,
    out: *mut *mut sym_result,
) -> sym_status {
    guard(|| {
        if out.is_null() {
            return Err(null("out"));
        }
        if vertices.is_null() {
            return Err(null("vertices"));
        }
        if triangles.is_null() {
            return Err(null("triangles"));
        }
        if num_vertices > ABSURD_COUNT || num_triangles > ABSURD_COUNT {
            return Err(invalid(format!("absurd sizes: {num_vertices} vertices, {num_triangles} triangles")));
        }
        let (params, mesh_params) = if params.is_null() {
            (Params::default(), MeshParams::default())
        } else {
            let p = params_ref(params, "params")?;
            (p.params.clone(), p.mesh.clone())
        };
        // SAFETY: non-NULL, lengths bounded above, and the caller guarantees the extent.
        let v = unsafe { std::slice::from_raw_parts(vertices, 3 * num_vertices) };
        let t = unsafe { std::slice::from_raw_parts(triangles, 3 * num_triangles) };
        let mesh = Mesh::from_slices(v, t, &mesh_params).map_err(|e| {
            let e = crate::Error::from(e);
            (from_error(&e), e.to_string())
        })?;
        let mut report = |f: f64| match progress {
            // SAFETY: the caller provides a valid function pointer and its user data.
            Some(cb) => unsafe { cb(f as f32, user_data) != 0 },
            None => true,
        };
        let det = detect(&mesh, &params, &mut report).map_err(|e| (from_error(&e), e.to_string()))?;
        let fmaps = det
            .symmetries
            .iter()
            .map(|s| {
                let k = s.fmap.nrows();
                (0..k * k).map(|i| s.fmap[(i / k, i % k)]).collect()
            })
            .collect();
        let pairs = det.symmetries.iter().map(|s| s.support_pairs.iter().flat_map(|&(a, b)| [a as i64, b as i64]).collect()).collect();
        let quality = det.vertex_symmetry();
        let r = Registry::insert(&RESULTS, RESULT_TAG, sym_result { det, fmaps, pairs, quality }) as *mut sym_result;
        // SAFETY: `out` is non-NULL and writable (caller contract).
        unsafe { *out = r };
        Ok(())
    })
}

/// Number of symmetries in a result (0 for NULL or an invalid handle).
#[no_mangle]
pub extern "C" fn sym_count(result: *const sym_result) -> usize {
    guard_value(0, || result_ref(result).map_or(0, |r| r.det.symmetries.len()))
}

/// Number of input vertices of the mesh a result describes (0 for NULL or an invalid handle).
#[no_mangle]
pub extern "C" fn sym_vertex_count(result: *const sym_result) -> usize {
    guard_value(0, || result_ref(result).map_or(0, |r| r.det.vertices))
}

/// Fills `*out` with symmetry `index` of `result`, in the report's order: strongest first, a
/// partial symmetry's score counting `sym_params_set_global_preference` (default 3) times less
/// against global ones (0 = what a viewer colours). The pointers in `*out` borrow from `result`
/// and stay valid until [`sym_free`]. `out->struct_size` must be set.
///
/// # Safety
/// `out` must point to a writable `sym_symmetry` whose `struct_size` is initialised.
#[no_mangle]
pub unsafe extern "C" fn sym_get_map(result: *const sym_result, index: usize, out: *mut sym_symmetry) -> sym_status {
    guard(|| {
        let r = result_ref(result)?;
        if out.is_null() {
            return Err(null("out"));
        }
        // The smallest version: up to `support_pairs` (0.1; later fields are written only when
        // `struct_size` covers them).
        let min = std::mem::offset_of!(sym_symmetry, support_pairs) + std::mem::size_of::<*const i64>();
        // SAFETY: `out` is non-NULL and its `struct_size` initialised (caller contract).
        let caller_size = unsafe { declared_size(out, "sym_symmetry", min) }?;
        let s = r.det.symmetries.get(index).ok_or_else(|| invalid(format!("index {index} out of range (count {})", r.det.symmetries.len())))?;
        let value = sym_symmetry {
            struct_size: std::mem::size_of::<sym_symmetry>().min(caller_size),
            source: s.source as i64,
            target: s.target as i64,
            kind: match s.kind {
                Kind::Global => sym_kind::SYM_KIND_GLOBAL,
                Kind::Partial => sym_kind::SYM_KIND_PARTIAL,
            },
            order: s.order as u32,
            group: s.group as u32,
            region_size: s.region_size,
            complexity: s.complexity,
            distortion: s.distortion,
            num_vertices: s.map.len(),
            map: s.map.as_ptr(),
            confidence: s.confidence.as_ptr(),
            fmap_size: s.fmap.nrows(),
            fmap: r.fmaps[index].as_ptr(),
            num_support_pairs: s.support_pairs.len(),
            support_pairs: r.pairs[index].as_ptr(),
            score: s.verdict.score,
            reversal: s.verdict.reversal,
            fixed: s.verdict.fixed,
            source_component: s.components[0] as u32,
            target_component: s.components[1] as u32,
        };
        // SAFETY: `out` has `caller_size` writable bytes (caller contract).
        unsafe { write_versioned(out, &value, caller_size) };
        Ok(())
    })
}

/// Dimension of the continuous family of isometries the shape has: 0 for none (most shapes),
/// 3 for a sphere, 1 for a surface of revolution (added in 0.3). When it is positive the
/// result lists one map per orientation type, samples of that family, not every sample voting
/// found. −1 for NULL or an invalid handle.
#[no_mangle]
pub extern "C" fn sym_continuous_dimension(result: *const sym_result) -> i32 {
    guard_value(-1, || result_ref(result).map_or(-1, |r| r.det.continuous.dimension as i32))
}

/// Fills `*out` with what validating the mesh found and decided (welded vertices,
/// non-manifold edges, ignored components and isolated vertices), so that a host can tell its
/// user (added in 0.3). `out->struct_size` must be set.
///
/// # Safety
/// `out` must point to a writable `sym_mesh_report` whose `struct_size` is initialised.
#[no_mangle]
pub unsafe extern "C" fn sym_get_mesh_report(result: *const sym_result, out: *mut sym_mesh_report) -> sym_status {
    guard(|| {
        let r = result_ref(result)?;
        if out.is_null() {
            return Err(null("out"));
        }
        // The smallest version: up to `collapsed_triangles` (0.3).
        let min = std::mem::offset_of!(sym_mesh_report, collapsed_triangles) + std::mem::size_of::<usize>();
        // SAFETY: `out` is non-NULL and its `struct_size` initialised (caller contract).
        let caller_size = unsafe { declared_size(out, "sym_mesh_report", min) }?;
        let i = &r.det.mesh;
        let value = sym_mesh_report {
            struct_size: std::mem::size_of::<sym_mesh_report>().min(caller_size),
            input_vertices: i.input_vertices,
            input_triangles: i.input_triangles,
            isolated_vertices: i.isolated_vertices,
            components: i.components,
            ignored_component_vertices: i.ignored_component_vertices,
            non_manifold_edges: i.non_manifold_edges,
            degenerate_triangles: i.degenerate_triangles,
            welded_vertices: i.welded_vertices,
            collapsed_triangles: i.collapsed_triangles,
            kept_components: i.kept_components,
            duplicate_triangles: i.duplicate_triangles,
            closed_holes: i.closed_holes,
        };
        // SAFETY: `out` has `caller_size` writable bytes (caller contract).
        unsafe { write_versioned(out, &value, caller_size) };
        Ok(())
    })
}

/// Writes `3 * num_vertices` bytes of `rgb`: the colours the command-line tool and the MeshLab
/// filter paint a map with, a vertex and its image alike (a symmetric function of their
/// positions; vertices with `map[v] < 0` or out of range are grey 150). `xyz` holds
/// `3 * num_vertices` coordinates and `map` `num_vertices` images (added in 0.3).
///
/// # Safety
/// `xyz`, `map` and `rgb` must point to arrays of the stated lengths.
#[no_mangle]
pub unsafe extern "C" fn sym_correspondence_colours(xyz: *const f64, num_vertices: usize, map: *const i64, rgb: *mut u8) -> sym_status {
    guard(|| {
        if xyz.is_null() {
            return Err(null("xyz"));
        }
        if map.is_null() {
            return Err(null("map"));
        }
        if rgb.is_null() {
            return Err(null("rgb"));
        }
        if num_vertices > ABSURD_COUNT {
            return Err(invalid(format!("absurd vertex count {num_vertices}")));
        }
        // SAFETY: non-NULL, bounded lengths; the caller guarantees the extents.
        let (xyz, map, rgb) = unsafe { (std::slice::from_raw_parts(xyz, 3 * num_vertices), std::slice::from_raw_parts(map, num_vertices), std::slice::from_raw_parts_mut(rgb, 3 * num_vertices)) };
        let vertices: Vec<[f64; 3]> = xyz.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
        for (out, c) in rgb.chunks_exact_mut(3).zip(crate::output::ply::correspondence_colours(&vertices, map)) {
            out.copy_from_slice(&c);
        }
        Ok(())
    })
}

/// Per-vertex symmetry summary (the largest confidence over all symmetries), `sym_vertex_count`
/// values borrowed from `result` until [`sym_free`]; NULL for NULL or an invalid handle.
#[no_mangle]
pub extern "C" fn sym_vertex_symmetry(result: *const sym_result) -> *const f64 {
    guard_value(std::ptr::null(), || result_ref(result).map_or(std::ptr::null(), |r| r.quality.as_ptr()))
}

/// Frees a result from [`sym_detect`]. NULL, a handle already freed, or a handle of another
/// type (a `sym_params`) is a no-op: nothing is freed.
#[no_mangle]
pub extern "C" fn sym_free(result: *mut sym_result) {
    guard_value((), || drop(Registry::remove(&RESULTS, result as usize)))
}

/// Copies the calling thread's last error message (empty after a success) into `buf` (at most
/// `len` bytes including the terminating NUL; truncated to fit) and stores the full message
/// length (without NUL) in `*out_len` when `out_len` is not NULL. `buf` may be NULL with
/// `len == 0` to query the length.
///
/// # Safety
/// `buf` must have `len` writable bytes; `out_len` must be NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn sym_last_error(buf: *mut c_char, len: usize, out_len: *mut usize) -> sym_status {
    let message = last_error();
    let status = guard(|| {
        if buf.is_null() && len > 0 {
            return Err(null("buf"));
        }
        if !out_len.is_null() {
            // SAFETY: non-NULL and writable by contract.
            unsafe { *out_len = message.len() };
        }
        if len > 0 {
            let n = message.len().min(len - 1);
            // SAFETY: buf has len ≥ n + 1 writable bytes.
            unsafe {
                std::ptr::copy_nonoverlapping(message.as_ptr(), buf.cast::<u8>(), n);
                *buf.add(n) = 0;
            }
        }
        Ok(())
    });
    // Reading the message must not erase it.
    if status == sym_status::SYM_STATUS_OK {
        set_error(message);
    }
    status
}
