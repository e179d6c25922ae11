//! Compile-time type names such as `dual-f32` built from the inner type's
//! [`anysl_core::ShadingFloat::NAME`], so that `Dual<F>` needs no per-type registration.

/// Capacity of a generated name, in bytes.
pub(crate) const NAME_CAP: usize = 64;

/// `prefix` followed by `inner`, as a fixed buffer and its used length.
pub(crate) const fn prefixed(prefix: &str, inner: &str) -> ([u8; NAME_CAP], usize) {
    let (p, q) = (prefix.as_bytes(), inner.as_bytes());
    assert!(p.len() + q.len() <= NAME_CAP, "anysl-ad: type name too long");
    let mut out = [0u8; NAME_CAP];
    let mut i = 0;
    while i < p.len() {
        out[i] = p[i];
        i += 1;
    }
    let mut j = 0;
    while j < q.len() {
        out[i + j] = q[j];
        j += 1;
    }
    (out, p.len() + q.len())
}

/// The first `len` bytes of `buf` as a string (both halves came from `&str`s, so UTF-8).
pub(crate) const fn as_str(buf: &'static [u8; NAME_CAP], len: usize) -> &'static str {
    match core::str::from_utf8(buf.split_at(len).0) {
        Ok(s) => s,
        Err(_) => panic!("anysl-ad: type name is not UTF-8"),
    }
}
