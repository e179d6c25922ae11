//! Helpers shared by the tests.
#![allow(dead_code)]

use anysl_rib::{parse_str, Options, Recorder, Report, Request, RibError};

/// Reads `text` into a [`Recorder`]; panics with the rendered diagnostics on error.
pub fn record(text: &str) -> Vec<Request> {
    record_with_report(text).0
}

/// Reads `text` into a [`Recorder`] and returns the report too.
pub fn record_with_report(text: &str) -> (Vec<Request>, Report) {
    let mut r = Recorder::new();
    match parse_str("test.rib", text, &mut r, &Options::default()) {
        Ok(report) => (r.requests, report),
        Err(e) => panic!("unexpected error:\n{}", e.render()),
    }
}

/// Reads `text` and returns the single request it holds.
pub fn one(text: &str) -> Request {
    let mut v = record(text);
    assert_eq!(v.len(), 1, "expected one request from {text:?}, got {v:?}");
    v.remove(0)
}

/// Reads `text`, which must fail, and returns the error.
pub fn fail(text: &str) -> RibError {
    let mut r = Recorder::new();
    match parse_str("test.rib", text, &mut r, &Options::default()) {
        Ok(rep) => panic!("expected an error from {text:?}; warnings:\n{}", rep.render_warnings()),
        Err(e) => e,
    }
}

/// The codes of the errors of `text`.
pub fn error_codes(text: &str) -> Vec<&'static str> {
    fail(text).errors().map(|d| d.code).collect()
}

/// `Debug` of a request without its locations (`loc: Loc { … }` removed), for compact comparisons.
pub fn show(r: &Request) -> String {
    let s = format!("{r:?}");
    let mut out = String::new();
    let mut rest = s.as_str();
    while let Some(i) = rest.find("loc: Loc {") {
        out.push_str(&rest[..i]);
        let after = &rest[i..];
        let close = after.find('}').map_or(after.len(), |c| c + 1);
        rest = after[close..].trim_start_matches(", ");
        rest = rest.strip_prefix(' ').unwrap_or(rest);
    }
    out.push_str(rest);
    out.replace(" { }", "").replace("{ , ", "{ ")
}

/// Unique temporary directory under the system temp dir, removed on drop.
pub struct TempDir(pub std::path::PathBuf);

impl TempDir {
    /// Creates `<tmp>/anysl-rib-<tag>-<pid>-<counter>`.
    pub fn new(tag: &str) -> Self {
        use std::sync::atomic::{AtomicUsize, Ordering};
        static N: AtomicUsize = AtomicUsize::new(0);
        let n = N.fetch_add(1, Ordering::Relaxed);
        let p = std::env::temp_dir().join(format!("anysl-rib-{tag}-{}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&p);
        std::fs::create_dir_all(&p).unwrap();
        Self(p)
    }

    /// Writes `text` to `rel` (creating directories) and returns the full path.
    pub fn write(&self, rel: &str, bytes: impl AsRef<[u8]>) -> std::path::PathBuf {
        let p = self.0.join(rel);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(&p, bytes).unwrap();
        p
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
