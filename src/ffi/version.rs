//! Version numbers.

/// ABI version: incremented on every incompatible change of the C interface.
pub const SYM_ABI_VERSION: u32 = 1;

/// The library version (`"MAJOR.MINOR.PATCH"`, from Cargo.toml), a static NUL-terminated string.
#[no_mangle]
pub extern "C" fn sym_version() -> *const std::ffi::c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// The ABI version of the loaded library (compare with `SYM_ABI_VERSION` from the header).
#[no_mangle]
pub extern "C" fn sym_abi_version() -> u32 {
    SYM_ABI_VERSION
}
