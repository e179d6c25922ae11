//! Type checker and lowering tests: the shaders and test programs of the repository, type
//! rules, overload resolution, uniform/varying rules, diagnostics (rendered text) and IR
//! snapshots (`insta`; bless with `INSTA_UPDATE=always` or `cargo insta review`).

use anysl_rsl::builtins::OVERLOADS;
use anysl_rsl::diag::Diagnostic;
use anysl_rsl::ir::{Module, Op};
use anysl_rsl::{compile_file, compile_source, CompileError, CompileOptions};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().expect("workspace root").to_path_buf()
}

fn sl_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|e| e == "sl")).collect())
        .unwrap_or_default();
    v.sort();
    v
}

fn compile(src: &str) -> Result<Module, CompileError> {
    compile_source("test.sl", src, &CompileOptions::default()).map(|c| c.module)
}

fn errors(src: &str) -> Vec<Diagnostic> {
    match compile_source("test.sl", src, &CompileOptions::default()) {
        Ok(_) => Vec::new(),
        Err(e) => e.diags.items,
    }
}

fn codes(src: &str) -> Vec<&'static str> {
    errors(src).iter().filter(|d| d.severity == anysl_rsl::diag::Severity::Error).map(|d| d.code).collect()
}

fn rendered(src: &str) -> String {
    match compile_source("test.sl", src, &CompileOptions::default()) {
        Ok(_) => String::new(),
        Err(e) => e.to_string(),
    }
}

/// The keys of every call in the module, in instruction order.
fn call_keys(m: &Module) -> Vec<&'static str> {
    m.func
        .insts
        .iter()
        .filter_map(|i| match &i.op {
            Op::Call { overload, .. } => Some(OVERLOADS[*overload as usize].key),
            _ => None,
        })
        .collect()
}

fn ok(src: &str) -> Module {
    match compile(src) {
        Ok(m) => m,
        Err(e) => panic!("expected no errors, got:\n{e}"),
    }
}

// ---- the repository's shaders and test programs ----------------------------------------------

#[test]
fn project_shaders_compile() {
    let r = root();
    let opts = CompileOptions { include_dirs: vec![r.join("shaders/rsl/include")], ..CompileOptions::default() };
    let mut files = sl_files(&r.join("shaders/rsl"));
    files.extend(sl_files(&r.join("shaders/rsl/standard")));
    assert!(files.len() >= 20, "expected the shaders/rsl ports");
    let mut failures = String::new();
    for f in &files {
        if let Err(e) = compile_file(f, &opts) {
            failures += &format!("{}:\n{e}\n", f.display());
        }
    }
    assert!(failures.is_empty(), "{failures}");
}

#[test]
fn conformance_programs_compile() {
    let files = sl_files(&root().join("tests/rsl/conformance"));
    let mut failures = String::new();
    for f in &files {
        if let Err(e) = compile_file(f, &CompileOptions::default()) {
            failures += &format!("{}:\n{e}\n", f.display());
        }
    }
    assert!(failures.is_empty(), "{failures}");
}

#[test]
fn diagnostics_programs_report_at_the_stated_position() {
    let files = sl_files(&root().join("tests/rsl/diagnostics"));
    let mut failures = String::new();
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap_or_default();
        let Some(at) = text.lines().find_map(|l| l.strip_prefix("// at:")) else { continue };
        let want = at.trim().to_string();
        match compile_file(f, &CompileOptions::default()) {
            Ok(_) => failures += &format!("{}: compiled without errors\n", f.display()),
            Err(e) => {
                let first = e.diags.items.iter().find(|d| d.severity == anysl_rsl::diag::Severity::Error);
                let loc = first.map(|d| e.sources.location(d.span)).unwrap_or_default();
                let got = loc.rsplitn(3, ':').take(2).collect::<Vec<_>>();
                let got = if got.len() == 2 { format!("{}:{}", got[1], got[0]) } else { loc.clone() };
                if got != want {
                    failures += &format!("{}: want {want}, got {got}\n{e}\n", f.display());
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures}");
}
