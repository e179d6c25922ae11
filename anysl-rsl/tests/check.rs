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
        .map(|d| {
            d.filter_map(|e| e.ok().map(|e| e.path())).filter(|p| p.extension().is_some_and(|e| e == "sl")).collect()
        })
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

/// The warning codes of a file that checks.
fn warnings(src: &str) -> Vec<&'static str> {
    match compile_source("test.sl", src, &CompileOptions::default()) {
        Ok(c) => c.warnings.items.iter().map(|d| d.code).collect(),
        Err(e) => panic!("expected no errors, got:\n{e}"),
    }
}

fn rendered(src: &str) -> String {
    match compile_source("test.sl", src, &CompileOptions::default()) {
        Ok(_) => String::new(),
        Err(e) => e.to_string().lines().map(str::trim_end).collect::<Vec<_>>().join("\n"),
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
    let files = sl_files(&root().join("tests/data/rsl/conformance"));
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
    let files = sl_files(&root().join("tests/data/rsl/diagnostics"));
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

#[test]
fn project_shader_ir_snapshots() {
    let r = root();
    let opts = CompileOptions { include_dirs: vec![r.join("shaders/rsl/include")], ..CompileOptions::default() };
    let mut files = sl_files(&r.join("shaders/rsl"));
    files.extend(sl_files(&r.join("shaders/rsl/standard")));
    for f in &files {
        let Ok(c) = compile_file(f, &opts) else { continue };
        let stem = f.file_stem().and_then(|s| s.to_str()).unwrap_or("x").to_string();
        insta::assert_snapshot!(format!("shader_{stem}"), c.module.to_string());
    }
}

// ---- type rules --------------------------------------------------------------------------------

/// The type of `expr` (after the declarations `decls`), read from the argument of a `printf`.
fn result_type(decls: &str, expr: &str) -> String {
    let src2 = format!("surface t() {{ {decls} if (1) {{ }} printf(\"\", {expr}); }}");
    let m2 = ok(&src2);
    // The printf argument is the instruction before the call.
    let call = m2
        .func
        .insts
        .iter()
        .rposition(|i| matches!(&i.op, Op::Call { builtin: anysl_rsl::builtins::Builtin::Printf, .. }));
    let arg = call.and_then(|c| m2.func.insts[c].args.get(1).copied()).expect("printf argument");
    m2.func.inst(arg).ty.to_string()
}

#[test]
fn operator_types() {
    let d = "point p = P; vector v = I; normal n = N; color c = Cs; float f = s; matrix m = 1; uniform float u = 1;";
    assert_eq!(result_type(d, "p - p"), "varying vector");
    assert_eq!(result_type(d, "p + v"), "varying point");
    assert_eq!(result_type(d, "v + p"), "varying point");
    assert_eq!(result_type(d, "p - v"), "varying point");
    assert_eq!(result_type(d, "n + n"), "varying normal");
    assert_eq!(result_type(d, "v * f"), "varying vector");
    assert_eq!(result_type(d, "f * c"), "varying color");
    assert_eq!(result_type(d, "c / 2"), "varying color");
    assert_eq!(result_type(d, "v . n"), "varying float");
    assert_eq!(result_type(d, "p ^ v"), "varying vector");
    assert_eq!(result_type(d, "m * m"), "varying matrix");
    assert_eq!(result_type(d, "u * 2"), "uniform float");
    assert_eq!(result_type(d, "-c"), "varying color");
    assert_eq!(result_type(d, "f > 0 ? c : 1"), "varying color");
    assert_eq!(result_type(d, "u > 0 ? 1 : 2"), "uniform float");
    assert_eq!(result_type(d, "color (1, 2, 3)"), "uniform color");
    assert_eq!(result_type(d, "point \"world\" (1, 2, 3)"), "uniform point");
    assert_eq!(result_type(d, "color \"hsv\" (f, 1, 1)"), "varying color");
    assert_eq!(result_type(d, "vector p"), "varying vector");
    assert_eq!(result_type(d, "(1, 2, 3)"), "uniform point");
}

#[test]
fn illegal_operands() {
    let cases = [
        "point p = P; color c = Cs; Ci = p + c;",
        "color c = Cs; float x = c < c;",
        "vector v = I; color c = v ^ v; Ci = c ^ c;",
        "string a = \"x\"; float x = a + 1;",
        "matrix m = 1; point p = m * P;",
    ];
    for c in cases {
        let got = codes(&format!("surface t() {{ {c} }}"));
        assert!(got.contains(&"E0205") || got.contains(&"E0204"), "{c}: {got:?}");
    }
}

#[test]
fn assignments_promote_and_convert() {
    let m = ok("surface t() { color c = 1; normal n = I; vector v = P - P; point p = v; matrix x = 2; Ci = c; }");
    let converts = m.func.insts.iter().filter(|i| matches!(i.op, Op::Convert)).count();
    assert_eq!(converts, 4);
    assert_eq!(codes("surface t() { color c = P; }"), ["E0204"]);
    assert_eq!(codes("surface t() { float f = Cs; }"), ["E0204"]);
    assert_eq!(codes("surface t() { string s = 1; }"), ["E0204"]);
}

#[test]
fn conditions_accept_floats_and_relations() {
    ok("surface t() { float x = s; if (x) Ci = 1; if (x > 0 && !(x < 1) || s == t) Ci = 0; while (0) {} }");
    assert_eq!(codes("surface t() { if (Cs) Ci = 1; }"), ["E0204"]);
    assert_eq!(codes("surface t() { float x = s > 0; }"), ["E0204"]);
}

// ---- overload resolution -----------------------------------------------------------------------

#[test]
fn overloads_resolve_by_argument_types() {
    let m = ok("surface t() {
        float a = mix(0, 1, s);
        color c = mix(Cs, 1, s);
        point p = mix(P, P, s);
        float d = distance(P, N);
        vector r = reflect(I, N);
        float l = length(I);
        float k = spline(s, 0, 1, 2, 3);
        color sc = spline(\"bezier\", s, Cs, Cs, Cs, Cs);
        float mx = max(s, t, 1, 2);
        Ci = c * a * d * l * k * mx + sc;
    }");
    assert_eq!(
        call_keys(&m),
        [
            "mix_fff",
            "mix_ccf",
            "mix_ppf",
            "distance_pp",
            "reflect_vv",
            "length_v",
            "spline_ffff_fs",
            "spline_sfccc_cs",
            "max_ff_fs"
        ]
    );
}

#[test]
fn noise_return_type_comes_from_context() {
    let m = ok("surface t() {
        float f = noise(P);
        color c = noise(P);
        vector v = noise(P, s);
        point p = point noise(s, t);
        Ci = color cellnoise(P) + c * f + noise(P);
        float g = 1 + 2 * noise(s);
    }");
    assert_eq!(
        call_keys(&m),
        ["noise_fp", "noise_cp", "noise_vpf", "noise_pff", "cellnoise_cp", "noise_cp", "noise_ff"]
    );
}

#[test]
fn output_arguments_become_slots() {
    let m = ok("surface t() { float kr, kt; vector R, T; fresnel(I, N, 1.5, kr, kt, R, T); fresnel(I, N, 1.5, kr, kt);
                Ci = kr + kt; point q = P; setxcomp(q, 1); float a[2]; setcomp(Ci, 0, a[1]); }");
    let calls: Vec<_> = m
        .func
        .insts
        .iter()
        .filter_map(|i| match &i.op {
            Op::Call { outputs, .. } => Some((i.args.len(), outputs.iter().filter(|o| o.is_some()).count())),
            _ => None,
        })
        .collect();
    assert_eq!(calls, [(3, 4), (3, 2), (1, 1), (2, 1)]);
    assert_eq!(codes("surface t() { fresnel(I, N, 1.5, 1, 2); }"), ["E0212", "E0212"]);
}

#[test]
fn bad_calls() {
    assert_eq!(codes("surface t() { Ci = normalize(\"x\"); }"), ["E0202"]);
    assert_eq!(codes("surface t() { float x = sin(1, 2); }"), ["E0203"]);
    assert_eq!(codes("surface t() { float x = sine(1); }"), ["E0201"]);
    let e = errors("surface t() { float x = sine(1); }");
    assert!(e[0].notes.iter().any(|n| n.contains("`sin`")), "{:?}", e[0].notes);
}

// ---- uniform / varying -------------------------------------------------------------------------

#[test]
fn uniform_varying_rules() {
    assert_eq!(codes("surface t() { uniform float u = s; }"), ["E0206"]);
    assert_eq!(codes("surface t(uniform float k = 1;) { k = s; }"), ["E0206"]);
    // A parameter uniform only by default, assigned a varying value, is made varying (Aqsis,
    // BMRT; K-3D's graphic_lines stores lighting into such a parameter).
    assert_eq!(warnings("surface t(float k = 1;) { k = s; Ci = k; }"), ["W0004"]);
    assert_eq!(ok("surface t(float k = 1;) { k = s; Ci = k; }").params[0].ty.to_string(), "varying float");
    // A uniform variable or parameter assigned under varying control flow is made varying
    // with a warning (what PRMan and BMRT did), and the IR stores it as varying.
    for src in [
        "surface t() { uniform float u = 0; if (s > 0.5) u = 1; }",
        "surface t() { uniform float u; float i; for (i = 0; i < s; i += 1) u = 1; }",
        "surface t(float k = 1;) { if (s > 0.5) k = 2; Ci = k; }",
    ] {
        assert_eq!(warnings(src), ["W0004"], "{src}");
    }
    // An illuminance body runs once per light: uniform statements are allowed there (PRMan;
    // Advanced RenderMan's lensflare), varying values still are not.
    assert!(warnings("surface t() { uniform float u = 0; illuminance(P) { u += 1; } Ci = u; }").is_empty());
    assert_eq!(codes("surface t() { uniform float u = 0; illuminance(P) { u += comp(Cl, 0); } }"), ["E0206"]);
    let m = ok("surface t() { uniform float u = 0; if (s > 0.5) u = 1; Ci = u; }");
    assert!(m.func.slots.iter().any(|s| s.name == "u" && s.ty.to_string() == "varying float"));
    let m = ok("surface t(uniform float k = 1;) { if (s > 0.5) k = 2; Ci = k; }");
    assert_eq!(m.params[0].ty.to_string(), "varying float");
    // A uniform output argument of a function stays an error: the caller's variable is uniform.
    assert_eq!(
        codes("void f(output uniform float u) { if (s > 0.5) u = 1; } surface t() { uniform float x = 0; f(x); }"),
        ["E0214"]
    );
    // Uniform flow is fine, as is a uniform declared inside the varying branch.
    ok("surface t(float k = 1;) { uniform float u = 0; if (k > 0) u = 1; if (s > 0) { uniform float w = 1; w = 2; } }");
    assert!(warnings("surface t(float k = 1;) { uniform float u = 0; if (k > 0) u = 1; }").is_empty());
    // A varying break makes the rest of the loop varying.
    assert_eq!(
        warnings("surface t() { uniform float u = 0, i; for (i = 0; i < 4; i += 1) { if (s > 0.5) break; u += 1; } }"),
        ["W0004", "W0004"] // `u` (for `u += 1`) and the counter `i` (its step `i += 1`)
    );
    // Function parameters take the caller's detail.
    ok("float twice(float x) { return 2 * x; } surface t() { uniform float u = twice(3); float v = twice(s); }");
    assert_eq!(codes("float twice(float x) { return 2 * x; } surface t() { uniform float u = twice(s); }"), ["E0206"]);
    assert_eq!(codes("float f(uniform float x) { return x; } surface t() { float v = f(s); }"), ["E0206"]);
}

// ---- functions ---------------------------------------------------------------------------------

#[test]
fn functions_inline_with_frames() {
    let m = ok("void bump(output float x; float by) { x += by; }
                float sq(float x) { return x * x; }
                surface t() { float a = 1; bump(a, sq(s)); Ci = a; }");
    let frames = m.func.body.iter().filter(|n| matches!(n, anysl_rsl::ir::Node::Frame(_))).count();
    assert_eq!(frames, 2);
    assert_eq!(codes("float f(float x) { return f(x); } surface t() { Ci = f(1); }"), ["E0217"]);
    assert_eq!(codes("float f(float x) { if (x > 0) return 1; } surface t() { Ci = f(1); }"), ["E0219"]);
    assert_eq!(codes("void f() { return 1; } surface t() { f(); }"), ["E0210"]);
    assert_eq!(codes("float f(float x) { x = 2; return x; } surface t() { Ci = f(1); }"), ["E0220"]);
    assert_eq!(codes("float f(float x) { return 1; } float f(float y) { return 2; } surface t() { }"), ["E0209"]);
    // Unused functions are still checked.
    assert_eq!(codes("float f(float x) { return x + undefined_thing; } surface t() { }"), ["E0200"]);
}

// ---- parameters --------------------------------------------------------------------------------

#[test]
fn parameter_defaults_are_constants() {
    let m = ok("surface t(float a = 2; float b = a * 3 - 1; color c = color \"hsv\" (0, 0, 1); point from = point \"shader\" (1, 2, 3);
                float ang = radians(30); float k[2] = {1, -2}; string n = \"x\"; output varying color o = 1; matrix mm = 1;) { }");
    let d: Vec<String> = m.params.iter().map(|p| p.default.to_string()).collect();
    assert_eq!(d[0], "2");
    assert_eq!(d[1], "5");
    assert_eq!(d[2], "(1, 1, 1)");
    assert_eq!(d[3], "(1, 2, 3)");
    assert_eq!(m.params[3].space.as_deref(), Some("shader"));
    assert!((m.params[4].default == anysl_rsl::ir::Const::Float(30f64.to_radians())));
    assert_eq!(d[5], "{1, -2}");
    assert!(m.params[7].output);
    assert_eq!(m.params[0].ty.to_string(), "uniform float");
    assert_eq!(m.params[7].ty.to_string(), "varying color");
    // A default that is not a constant is computed when the shader runs (W0006): the
    // parameter is made varying (unless a string), its constant default is zero, and a hidden
    // flag parameter, 1 by default, says that the parameter keeps its default.
    assert_eq!(warnings("surface t(float a = s;) { }"), ["W0006"]);
    let m = ok("surface t(float a = noise(1); vector d = normalize(dPdu); string n = concat(\"a\", \"b\");) { }");
    assert_eq!(m.params.len(), 6);
    assert_eq!(m.params[0].ty.to_string(), "varying float");
    assert_eq!(m.params[1].ty.to_string(), "varying vector");
    assert_eq!(m.params[2].ty.to_string(), "uniform string");
    assert_eq!(m.params[3].name, "__default_a");
    assert_eq!(m.params[3].default, anysl_rsl::ir::Const::Float(1.0));
    assert_eq!(m.params[5].name, "__default_n");
    // Errors in such a default stay errors; a type mismatch is one.
    assert_eq!(codes("surface t(float a = nosuch(s);) { }"), ["E0201"]);
    assert_eq!(codes("surface t(float a = Cs;) { }"), ["E0204"]);
    assert_eq!(codes("surface t(float a = \"x\";) { }"), ["E0204"]);
}

// ---- diagnostics -------------------------------------------------------------------------------

#[test]
fn twenty_kinds_of_diagnostics() {
    let cases: &[(&str, &str)] = &[
        ("E0001", "surface t() { Ci = 1 @ 2; }"),
        ("E0002", "surface t() { string s = \"abc; }"),
        ("E0010", "#include \"nope_not_here.h\"\nsurface t() { }"),
        ("E0012", "#if 1\nsurface t() { }"),
        ("E0100", "surface t() { Ci = ; }"),
        ("E0200", "surface t() { Ci = colour; }"),
        ("E0201", "surface t() { Ci = nosuch(1); }"),
        ("E0202", "surface t() { Ci = normalize(\"x\"); }"),
        ("E0203", "surface t() { float x = sin(); }"),
        ("E0204", "surface t() { float x = Cs; }"),
        ("E0205", "surface t() { Ci = P + Cs; }"),
        ("E0206", "surface t() { uniform float u = s; }"),
        ("E0207", "surface t() { xcomp(P) = 1; }"),
        ("E0208", "surface t() { break; }"),
        ("E0209", "surface t() { float a; float a; }"),
        ("E0210", "float f() { return Cs; } surface t() { Ci = f(); }"),
        ("E0211", "surface t() { illuminate(P) { } }"),
        ("E0212", "void f(output float x) { x = 1; } surface t() { f(2); }"),
        ("E0213", "surface t() { float a = 1; Ci = a[0]; }"),
        ("E0214", "void f(output uniform float u) { if (s > 0) u = 1; } surface t() { uniform float x = 0; f(x); }"),
        ("E0215", "surface t() { float a[2] = {1, 2, 3}; }"),
        ("E0216", "surface t(float k;) { }"),
        ("E0217", "float f() { return f(); } surface t() { Ci = f(); }"),
        ("E0218", "float f() { return 1; }"),
        ("E0219", "float f() { } surface t() { Ci = f(); }"),
        ("E0220", "surface t() { Ng = N; }"),
        ("E0221", "surface t() { gather(\"illuminance\", P, N, 1, 8) { } }"),
    ];
    let mut seen = std::collections::BTreeSet::new();
    for (code, src) in cases {
        let got = codes(src);
        assert!(got.contains(code), "{src}: want {code}, got {got:?}\n{}", rendered(src));
        seen.insert(*code);
    }
    assert!(seen.len() >= 20);
}

#[test]
fn several_errors_per_run_without_cascades() {
    let got = codes("surface t() { float a = undefined1; float b = a + undefined2 * 3; Ci = P + Cs; Ng = 1; }");
    assert_eq!(got, ["E0200", "E0200", "E0205", "E0220"]);
}

#[test]
fn rendered_unknown_name() {
    let r = rendered("surface t()\n{\n    float kd = 1;\n    Ci = Kd * Cs;\n}\n");
    insta::assert_snapshot!(r, @r"
    error[E0200]: unknown variable `Kd`
      ┌─ test.sl:4:10
      │
    4 │     Ci = Kd * Cs;
      │          ^^ not declared
      │
      = did you mean `kd`?
    ");
}

#[test]
fn rendered_bad_operands() {
    let r = rendered("surface t()\n{\n    Ci = P + Cs;\n}\n");
    insta::assert_snapshot!(r, @r"
    error[E0205]: binary operation `+` between a point and a color is illegal
      ┌─ test.sl:3:10
      │
    3 │     Ci = P + Cs;
      │          ^^^^^^ point + color
      │
      = colors and points do not mix; cast one side, e.g. `color (…)` or `vector (…)`
    ");
}

#[test]
fn rendered_read_only_global() {
    let r = rendered("surface t()\n{\n    Ng = N;\n}\n");
    insta::assert_snapshot!(r, @r"
    error[E0220]: assignment to the read-only global Ng in a surface shader
      ┌─ test.sl:3:5
      │
    3 │     Ng = N;
      │     ^^ read-only here
      │
      = a surface shader may assign P, N, Ci, Oi
    ");
}

#[test]
fn rendered_varying_to_uniform() {
    let r = rendered("surface t()\n{\n    uniform float k = 0;\n    k = s * 2;\n}\n");
    insta::assert_snapshot!(r, @r"
    error[E0206]: a varying value cannot be assigned to the uniform variable `k`
      ┌─ test.sl:4:5
      │
    4 │     k = s * 2;
      │     ^   ----- varying value
      │     │
      │     uniform variable
      │
      = declare `k` varying, or compute it from uniform values only
    ");
}

#[test]
fn rendered_no_overload() {
    let r = rendered("surface t()\n{\n    Ci = normalize(\"up\");\n}\n");
    insta::assert_snapshot!(r, @r#"
    error[E0202]: no overload of `normalize` takes a string
      ┌─ test.sl:3:10
      │
    3 │     Ci = normalize("up");
      │          ^^^^^^^^^^^^^^^ called with (string)
      │
      = candidates:
          vector normalize(vector)
          vector normalize(point)
          normal normalize(normal)
    "#);
}

#[test]
fn rendered_break_level() {
    let r = rendered("surface t()\n{\n    while (1) {\n        break 2;\n    }\n}\n");
    insta::assert_snapshot!(r, @r"
    error[E0208]: `break 2` inside only 1 loop
      ┌─ test.sl:4:9
      │
    4 │         break 2;
      │         ^^^^^^^^ level too deep
      │
      = `break n` leaves n enclosing loops (while, for, illuminance); n must be between 1 and 1
    ");
}

#[test]
fn rendered_missing_return() {
    let r = rendered("float f(float x)\n{\n    if (x > 0)\n        return 1;\n}\nsurface t() { Ci = f(s); }\n");
    insta::assert_snapshot!(r, @r"
    error[E0219]: function `f` may end without returning a float
      ┌─ test.sl:1:7
      │
    1 │ float f(float x)
      │       ^ non-void function
      ·
    5 │ }
      │ - control can reach the end here
      │
      = add a `return` at the end of the function
    ");
}

#[test]
fn never_panics_on_odd_programs() {
    let progs = [
        "",
        "surface",
        "surface t(",
        "surface t() { Ci = (1, 2); }",
        "surface t() { float a[0]; a[1] = 2; }",
        "surface t() { Ci = ((((((((1)))))))); }",
        "surface t() { return 1; }",
        "surface t() { float x = texture(\"a\"[2], s, t); }",
        "surface t() { Ci = color \"nosuch\" (1, 2, 3); }",
        "surface t() { break 0; continue 3; }",
        "light l() { illuminance(P) { } solar() { Cl = 1; } }",
        "displacement d() { P = P + N; N = calculatenormal(P); Ci = 1; }",
        "imager i() { Ci = 1; alpha = 1; P = 1; }",
        "volume v() { Ci = 1; illuminance(P) { Ci += Cl; } }",
        "surface a() {} surface b() {}",
        "void f(float a[]) { } surface t() { float b[3]; f(b); f(1); }",
        "surface t() { matrix m = (1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16); matrix n = (1, 2, 3, 4); }",
    ];
    for p in progs {
        let _ = compile(p);
    }
}

// ---- lowering of every statement kind (IR snapshots) -------------------------------------------

#[test]
fn lowering_snapshot_surface_statements() {
    let m = ok(r#"
float sq(float x) { return x * x; }
void accumulate(output color acc; color c) { acc += c; }
surface stmts(float Kd = 0.5; string cat = "";)
{
    float a[3] = {1, 2, 3};
    float i, x = 0;
    color acc = 0;
    ;
    { float inner = 1; x = inner; }
    if (s > 0.5) x = 1; else if (t > 0.5) x = 2; else x = sq(s);
    while (x < 4) { x += 1; if (x > 3) continue; }
    for (i = 0; i < 3; i += 1) {
        a[i] = a[i] * 2;
        while (1) { break 2; }
    }
    illuminance(cat, P, N, PI / 2) {
        accumulate(acc, Cl * (normalize(L) . N));
        if (x > 2) break;
    }
    illuminance(P) { acc += Cl; }
    Ci = Kd * acc + color "hsv" (x / 4, 1, 1) + noise(P);
    Oi = x > 1 ? 1 : Os;
    return;
}
"#);
    insta::assert_snapshot!("stmts_surface", m.to_string());
}

#[test]
fn lowering_snapshot_light_statements() {
    let m = ok(r#"
light lights(float intensity = 1; point from = point "shader" (0, 0, 0); vector dir = vector (0, 0, 1);)
{
    illuminate(from) { Cl = intensity / (L . L); }
    illuminate(from, dir, 0.5) { Cl += 1; }
    solar(dir, 0) { Cl += 2; }
    solar() { Cl += 3; }
}
"#);
    insta::assert_snapshot!("stmts_light", m.to_string());
}

#[test]
fn lowering_snapshot_displacement_and_matrices() {
    let m = ok(r#"
displacement bump(float Km = 1; matrix xf = 1;)
{
    matrix m = matrix "world" (1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1) * xf;
    point q = transform(m, P);
    float amp = Km * float texture("bumps.tx", s, t, "blur", 0.1);
    P += amp * normalize(N) + vector q * 0;
    N = calculatenormal(P);
}
"#);
    insta::assert_snapshot!("stmts_displacement", m.to_string());
}
