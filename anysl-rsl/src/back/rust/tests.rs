//! Unit tests of the Rust generator on small programs (the generated code itself is compiled
//! and run by the `anysl-tests` crate).

use super::*;
use crate::{compile_source, CompileOptions};

fn gen(src: &str) -> String {
    let c = compile_source("t.sl", src, &CompileOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    generate_with_sources(
        &crate::passes::optimize(c.module.clone(), &Default::default()),
        Some(&c.sources),
        &RustOptions::default(),
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn type_names() {
    assert_eq!(type_name("pointlight"), "PointLight");
    assert_eq!(type_name("wood"), "Wood");
    assert_eq!(type_name("t_mix_color"), "TMixColor");
    assert_eq!(type_name("t_2d"), "T2D");
}

#[test]
fn uniform_branch_is_a_rust_if_and_varying_branch_a_mask() {
    let r = gen("surface t(uniform float Ks = 0.5;) { if (Ks != 0) Ci = 1; if (s > 0.5) Ci = 2; }");
    assert!(r.contains("if (self.Ks != 0.0_f64)") || r.contains("if v"), "{r}");
    assert!(r.contains(".any() {"), "{r}");
    assert!(r.contains("Blend::<F>::blend("), "{r}");
}

#[test]
fn trace_inside_illuminance_is_an_error() {
    let c = compile_source("t.sl", "surface t() { illuminance(P) { Ci += trace(P, L); } }", &CompileOptions::default())
        .unwrap();
    let e = generate(&crate::passes::optimize(c.module, &Default::default()), &RustOptions::default()).unwrap_err();
    assert!(e.to_string().contains("cannot call `trace` inside an `illuminance` body"), "{e}");
}
