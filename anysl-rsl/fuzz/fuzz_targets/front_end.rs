//! Fuzzes the RSL front end (preprocessor + parser) on arbitrary UTF-8: it must never panic,
//! overflow the stack or hang. Run with `cargo +nightly fuzz run front_end` from `anysl-rsl/`.
//! Includes are served from an empty in-memory file system so that inputs such as
//! `#include "/dev/zero"` cannot touch the disk.
#![no_main]

use anysl_rsl::diag::Diagnostics;
use anysl_rsl::front::{self, PpOptions};
use anysl_rsl::span::SourceMap;
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|text: &str| {
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let mut no_files = |_: &Path| -> Option<String> { None };
    let opts = PpOptions { include_dirs: vec!["inc".into()], defines: vec![("FUZZ".into(), Some("1".into()))] };
    let unit = front::parse_source_with(&mut sources, "fuzz.sl", text, &opts, &mut no_files, &mut diags);
    let _ = diags.render(&sources);
    let _ = unit.expr_count;
});
