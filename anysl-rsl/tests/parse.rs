//! Front-end tests: lexer + preprocessor + parser.
//!
//! Every statement and expression form, operator precedence (printed as S-expressions),
//! the preprocessor (include search order, macros, conditionals, line tracking), rendered
//! diagnostics compared as exact text, every `.sl` file in the repository, deep nesting, and
//! property tests that the front end never panics and always ends.

use anysl_rsl::diag::{codes, Diagnostics};
use anysl_rsl::front::ast::*;
use anysl_rsl::front::{self, PpOptions};
use anysl_rsl::span::SourceMap;
use proptest::prelude::*;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

// ---- helpers -------------------------------------------------------------------------------------

/// Parses `src` with in-memory include files.
fn parse_mem(src: &str, files: &[(&str, &str)], opts: &PpOptions) -> (Unit, Diagnostics, SourceMap) {
    let map: HashMap<PathBuf, String> = files.iter().map(|(p, t)| (PathBuf::from(p), (*t).to_owned())).collect();
    let mut loader = |p: &Path| map.get(p).cloned();
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let unit = front::parse_source_with(&mut sources, "main.sl", src, opts, &mut loader, &mut diags);
    (unit, diags, sources)
}

fn parse_ok(src: &str) -> Unit {
    let (unit, diags, sources) = parse_mem(src, &[], &PpOptions::default());
    assert!(!diags.has_errors(), "unexpected errors:\n{}", diags.render(&sources));
    unit
}

fn errors(src: &str) -> (Vec<&'static str>, String) {
    let (_, diags, sources) = parse_mem(src, &[], &PpOptions::default());
    (diags.items.iter().map(|d| d.code).collect(), diags.render(&sources))
}

/// S-expression of an expression: shows the tree shape (and so precedence).
fn sx(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Number(v) => format!("{v}"),
        ExprKind::Str(s) => format!("{s:?}"),
        ExprKind::Name(n) => n.clone(),
        ExprKind::Unary(op, a) => format!("({} {})", if *op == UnaryOp::Neg { "neg" } else { "!" }, sx(a)),
        ExprKind::Binary(op, a, b) => format!("({} {} {})", op.symbol(), sx(a), sx(b)),
        ExprKind::Ternary(c, a, b) => format!("(? {} {} {})", sx(c), sx(a), sx(b)),
        ExprKind::Assign(op, a, b) => {
            let s = match op {
                AssignOp::Assign => "=",
                AssignOp::Add => "+=",
                AssignOp::Sub => "-=",
                AssignOp::Mul => "*=",
                AssignOp::Div => "/=",
            };
            format!("({s} {} {})", sx(a), sx(b))
        }
        ExprKind::Call(f, args) => {
            let mut s = format!("(call {}", f.name);
            for a in args {
                let _ = write!(s, " {}", sx(a));
            }
            s + ")"
        }
        ExprKind::Triple(t) => format!("(triple {} {} {})", sx(&t[0]), sx(&t[1]), sx(&t[2])),
        ExprKind::MatrixLit(v) => format!("(matrix {})", v.iter().map(sx).collect::<Vec<_>>().join(" ")),
        ExprKind::ArrayInit(v) => format!("{{{}}}", v.iter().map(sx).collect::<Vec<_>>().join(" ")),
        ExprKind::Index(a, i) => format!("(index {} {})", sx(a), sx(i)),
        ExprKind::Cast { to, space, expr } => match space {
            Some(s) => format!("(cast {to} {} {})", sx(s), sx(expr)),
            None => format!("(cast {to} {})", sx(expr)),
        },
    }
}

/// The body statements of the first item.
fn body(unit: &Unit) -> &[Stmt] {
    match &unit.items[0] {
        Item::Shader(s) => &s.body.stmts,
        Item::Function(f) => &f.body.stmts,
    }
}

/// The S-expression of `expr` parsed as an expression statement.
fn expr_sx(expr: &str) -> String {
    let unit = parse_ok(&format!("surface t() {{ {expr}; }}"));
    match &body(&unit)[0].kind {
        StmtKind::Expr(e) => sx(e),
        k => panic!("not an expression statement: {k:?}"),
    }
}

/// Collects every expression id in a unit.
fn collect_ids(unit: &Unit) -> Vec<u32> {
    fn e(x: &Expr, out: &mut Vec<u32>) {
        out.push(x.id.0);
        match &x.kind {
            ExprKind::Unary(_, a) => e(a, out),
            ExprKind::Binary(_, a, b) | ExprKind::Assign(_, a, b) | ExprKind::Index(a, b) => {
                e(a, out);
                e(b, out);
            }
            ExprKind::Ternary(a, b, c) => {
                e(a, out);
                e(b, out);
                e(c, out);
            }
            ExprKind::Call(_, v) | ExprKind::MatrixLit(v) | ExprKind::ArrayInit(v) => v.iter().for_each(|a| e(a, out)),
            ExprKind::Triple(t) => t.iter().for_each(|a| e(a, out)),
            ExprKind::Cast { space, expr, .. } => {
                if let Some(s) = space {
                    e(s, out);
                }
                e(expr, out);
            }
            _ => {}
        }
    }
    fn s(x: &Stmt, out: &mut Vec<u32>) {
        match &x.kind {
            StmtKind::Expr(a) | StmtKind::Return(Some(a)) => e(a, out),
            StmtKind::Decl { vars, .. } => vars.iter().filter_map(|v| v.init.as_ref()).for_each(|a| e(a, out)),
            StmtKind::Block(b) => b.stmts.iter().for_each(|x| s(x, out)),
            StmtKind::If { cond, then, otherwise } => {
                e(cond, out);
                s(then, out);
                otherwise.iter().for_each(|x| s(x, out));
            }
            StmtKind::While { cond, body } => {
                e(cond, out);
                s(body, out);
            }
            StmtKind::For { init, cond, step, body } => {
                [init, cond, step].into_iter().flatten().for_each(|a| e(a, out));
                s(body, out);
            }
            StmtKind::Illuminance { category, position, cone, body } => {
                category.iter().for_each(|a| e(a, out));
                e(position, out);
                cone.iter().for_each(|(a, b)| {
                    e(a, out);
                    e(b, out)
                });
                s(body, out);
            }
            StmtKind::Illuminate { position, cone, body } => {
                e(position, out);
                cone.iter().for_each(|(a, b)| {
                    e(a, out);
                    e(b, out)
                });
                s(body, out);
            }
            StmtKind::Solar { cone, body } => {
                cone.iter().for_each(|(a, b)| {
                    e(a, out);
                    e(b, out)
                });
                s(body, out);
            }
            StmtKind::Gather { args, body, otherwise } => {
                args.iter().for_each(|a| e(a, out));
                s(body, out);
                otherwise.iter().for_each(|x| s(x, out));
            }
            StmtKind::Function(f) => f.body.stmts.iter().for_each(|x| s(x, out)),
            _ => {}
        }
    }
    let mut out = Vec::new();
    for it in &unit.items {
        let (params, b) = match it {
            Item::Shader(sh) => (&sh.params, &sh.body),
            Item::Function(f) => (&f.params, &f.body),
        };
        params.iter().filter_map(|p| p.default.as_ref()).for_each(|a| e(a, &mut out));
        b.stmts.iter().for_each(|x| s(x, &mut out));
    }
    out
}

// ---- definitions ---------------------------------------------------------------------------------

#[test]
fn shader_kinds_and_parameter_groups() {
    let unit = parse_ok(
        "surface s(float Ka = 1, Kd = .5; color c = 1;) {}
         light l() {} displacement d() {} volume v() {} imager i() {}",
    );
    let kinds: Vec<ShaderType> = unit
        .items
        .iter()
        .map(|i| match i {
            Item::Shader(s) => s.kind,
            Item::Function(_) => panic!(),
        })
        .collect();
    use ShaderType::*;
    assert_eq!(kinds, vec![Surface, Light, Displacement, Volume, Imager]);
    let Item::Shader(s) = &unit.items[0] else { panic!() };
    let names: Vec<(&str, anysl_rsl::types::BaseType)> =
        s.params.iter().map(|p| (p.name.name.as_str(), p.ty.base)).collect();
    use anysl_rsl::types::BaseType as B;
    assert_eq!(names, vec![("Ka", B::Float), ("Kd", B::Float), ("c", B::Color)]);
    assert_eq!(sx(s.params[1].default.as_ref().unwrap()), "0.5");
}

#[test]
fn parameter_details_outputs_and_arrays() {
    let unit = parse_ok(
        "surface s(output varying color o = 0; uniform output float u = 1; float a[3] = {1, 2, 3};
                   uniform string map = \"\";) {}
         float f(float x, y; output color c; float arr[]; vector v) { return 1; }
         float g(float a, float b) { return a; }",
    );
    let Item::Shader(s) = &unit.items[0] else { panic!() };
    use anysl_rsl::types::Detail;
    assert!(s.params[0].output && s.params[0].ty.detail == Some(Detail::Varying));
    assert!(s.params[1].output && s.params[1].ty.detail == Some(Detail::Uniform));
    assert_eq!(s.params[2].array, Some(Some(3)));
    assert_eq!(sx(s.params[2].default.as_ref().unwrap()), "{1 2 3}");
    let Item::Function(f) = &unit.items[1] else { panic!() };
    let names: Vec<&str> = f.params.iter().map(|p| p.name.name.as_str()).collect();
    assert_eq!(names, vec!["x", "y", "c", "arr", "v"]);
    assert!(f.params[2].output);
    assert_eq!(f.params[3].array, Some(None));
    let Item::Function(g) = &unit.items[2] else { panic!() };
    assert_eq!(g.params.len(), 2);
}

#[test]
fn functions_typed_untyped_void_and_nested() {
    let unit = parse_ok(
        "void v() { }
         helper() { }
         uniform float u() { return 1; }
         surface s() {
             float inner(float x) { return x * 2; }
             color c(float y) { extern color Cs; return Cs * y; }
             untyped() { }
             Ci = inner(1);
         }",
    );
    use anysl_rsl::types::BaseType as B;
    let Item::Function(v) = &unit.items[0] else { panic!() };
    assert_eq!(v.ret.base, B::Void);
    let Item::Function(h) = &unit.items[1] else { panic!() };
    assert_eq!((h.ret.base, h.name.name.as_str()), (B::Void, "helper"));
    let Item::Function(u) = &unit.items[2] else { panic!() };
    assert_eq!(u.ret.detail, Some(anysl_rsl::types::Detail::Uniform));
    let stmts = body(&Unit { items: vec![unit.items[3].clone()], expr_count: 0 }).to_vec();
    assert!(matches!(&stmts[0].kind, StmtKind::Function(f) if f.name.name == "inner" && f.ret.base == B::Float));
    let StmtKind::Function(c) = &stmts[1].kind else { panic!() };
    assert!(matches!(&c.body.stmts[0].kind, StmtKind::Decl { is_extern: true, .. }));
    assert!(matches!(&stmts[2].kind, StmtKind::Function(f) if f.name.name == "untyped"));
    assert!(matches!(&stmts[3].kind, StmtKind::Expr(_)));
}

// ---- statements ----------------------------------------------------------------------------------

#[test]
fn every_statement_form() {
    let unit = parse_ok(
        r#"surface s() {
            ;
            float a = 1, b[2] = {1, 2}, c;
            uniform color u;
            varying point p = point "world" (0, 0, 0);
            extern normal N;
            { a = 2; }
            if (a > 1) a = 1; else { a = 0; }
            if (a) a = 2;
            while (a < 10) a += 1;
            for (a = 0; a < 3; a += 1) { break; continue; break 2; continue 2; }
            for (;;) break;
            illuminance(P) { }
            illuminance("spec", P) { }
            illuminance(P, N, 1.57) ;
            illuminance("-env", P, N, 1.57) ;
            gather("illuminance", P, N, 0.5, 16, "surface:Ci", c) a = 1; else a = 0;
            gather("illuminance", P, N, 0.5, 16) { }
            return;
            return a + 1;
        }
        light l() { illuminate(P) Cl = 1; illuminate(P, N, 1) { } solar() { } solar(vector (0,0,1), 0) { } }"#,
    );
    let kinds: Vec<String> = body(&unit)
        .iter()
        .map(|s| {
            let d = format!("{:?}", s.kind);
            d.split(|c: char| !c.is_alphanumeric()).next().unwrap_or("").to_owned()
        })
        .collect();
    assert_eq!(
        kinds,
        [
            "Empty",
            "Decl",
            "Decl",
            "Decl",
            "Decl",
            "Block",
            "If",
            "If",
            "While",
            "For",
            "For",
            "Illuminance",
            "Illuminance",
            "Illuminance",
            "Illuminance",
            "Gather",
            "Gather",
            "Return",
            "Return"
        ]
    );
    let st = body(&unit);
    let StmtKind::Decl { vars, .. } = &st[1].kind else { panic!() };
    assert_eq!((vars.len(), vars[1].array, vars[2].init.is_none()), (3, Some(2), true));
    assert!(matches!(&st[4].kind, StmtKind::Decl { is_extern: true, .. }));
    let StmtKind::If { otherwise, .. } = &st[6].kind else { panic!() };
    assert!(otherwise.is_some());
    let StmtKind::For { body: fb, .. } = &st[9].kind else { panic!() };
    let StmtKind::Block(b) = &fb.kind else { panic!() };
    let lv: Vec<String> = b.stmts.iter().map(|s| format!("{:?}", s.kind)).collect();
    assert_eq!(lv, ["Break(None)", "Continue(None)", "Break(Some(2))", "Continue(Some(2))"]);
    let StmtKind::For { init, cond, step, .. } = &st[10].kind else { panic!() };
    assert!(init.is_none() && cond.is_none() && step.is_none());
    let cats: Vec<(Option<String>, bool)> = st[11..15]
        .iter()
        .map(|s| match &s.kind {
            StmtKind::Illuminance { category, cone, .. } => (category.as_ref().map(sx), cone.is_some()),
            _ => panic!(),
        })
        .collect();
    assert_eq!(cats, [(None, false), (Some("\"spec\"".into()), false), (None, true), (Some("\"-env\"".into()), true)]);
    let StmtKind::Gather { args, otherwise, .. } = &st[15].kind else { panic!() };
    assert_eq!((args.len(), otherwise.is_some()), (7, true));
    let StmtKind::Gather { otherwise, .. } = &st[16].kind else { panic!() };
    assert!(otherwise.is_none());
    let Item::Shader(l) = &unit.items[1] else { panic!() };
    let lk: Vec<(bool, &str)> = l
        .body
        .stmts
        .iter()
        .map(|s| match &s.kind {
            StmtKind::Illuminate { cone, .. } => (cone.is_some(), "illuminate"),
            StmtKind::Solar { cone, .. } => (cone.is_some(), "solar"),
            _ => panic!(),
        })
        .collect();
    assert_eq!(lk, [(false, "illuminate"), (true, "illuminate"), (false, "solar"), (true, "solar")]);
}

#[test]
fn unsized_local_arrays_take_the_initializer_length() {
    let unit = parse_ok("surface s() { float a[] = {1, 2, 3}; }");
    let StmtKind::Decl { vars, .. } = &body(&unit)[0].kind else { panic!() };
    assert_eq!(vars[0].array, Some(3));
    let (c, r) = errors("surface s() { float a[]; }");
    assert_eq!(c, [codes::SYNTAX]);
    assert!(r.contains("array `a` needs a length"), "{r}");
}

#[test]
fn illuminance_with_message_passing_extras_warns() {
    let (unit, diags, _) = parse_mem(
        "surface s() { illuminance(\"c\", P, N, 1, \"lightcache\", \"refresh\") {} }",
        &[],
        &PpOptions::default(),
    );
    assert!(!diags.has_errors());
    assert_eq!(diags.items.len(), 1);
    assert_eq!(diags.items[0].code, codes::UNSUPPORTED);
    assert!(matches!(&body(&unit)[0].kind, StmtKind::Illuminance { category: Some(_), cone: Some(_), .. }));
}

#[test]
fn loop_statement_argument_counts() {
    let (c, r) = errors("light l() { illuminate(P, N) {} solar(N) {} } surface s() { illuminance() {} }");
    assert_eq!(c, [codes::SYNTAX, codes::SYNTAX, codes::SYNTAX], "{r}");
    assert!(r.contains("`illuminate` takes 1 or 3 arguments, not 2"), "{r}");
    assert!(r.contains("`solar` takes 0 or 2 arguments, not 1"), "{r}");
}

// ---- expressions ---------------------------------------------------------------------------------

#[test]
fn primaries() {
    assert_eq!(expr_sx("f()"), "(call f)");
    assert_eq!(expr_sx("f(1, \"a\", x)"), "(call f 1 \"a\" x)");
    assert_eq!(expr_sx("(1, 2, 3)"), "(triple 1 2 3)");
    assert_eq!(expr_sx("(1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1)"), "(matrix 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1)");
    assert_eq!(expr_sx("a = {1, 2, 3,}"), "(= a {1 2 3})");
    assert_eq!(expr_sx("a[i + 1]"), "(index a (+ i 1))");
    assert_eq!(expr_sx("texture(\"map.tx\"[1], s, t)"), "(call texture (index \"map.tx\" 1) s t)");
    assert_eq!(expr_sx("surface(\"Kd\", k)"), "(call surface \"Kd\" k)");
    assert_eq!(expr_sx("displacement(\"amp\", k)"), "(call displacement \"amp\" k)");
    assert_eq!(expr_sx("((a))"), "a");
}

#[test]
fn casts_and_space_constructors() {
    assert_eq!(expr_sx("color \"hsv\" (h, s, v)"), "(cast color \"hsv\" (triple h s v))");
    assert_eq!(expr_sx("point \"world\" (0, 0, 0)"), "(cast point \"world\" (triple 0 0 0))");
    assert_eq!(expr_sx("y = float x"), "(= y (cast float x))");
    assert_eq!(expr_sx("y = vector P"), "(= y (cast vector P))");
    assert_eq!(expr_sx("color 1"), "(cast color 1)");
    assert_eq!(expr_sx("matrix \"shader\" 1"), "(cast matrix \"shader\" 1)");
    assert_eq!(expr_sx("normal (0, 0, 1)"), "(cast normal (triple 0 0 1))");
    assert_eq!(expr_sx("string \"s\""), "(cast string \"s\")");
    // A cast binds like a unary operator.
    assert_eq!(expr_sx("color 1 * Kd"), "(* (cast color 1) Kd)");
    assert_eq!(expr_sx("y = float noise(P) * 2"), "(= y (* (cast float (call noise P)) 2))");
    assert_eq!(expr_sx("-color 1"), "(neg (cast color 1))");
}

#[test]
fn precedence_and_associativity() {
    assert_eq!(expr_sx("a + b * c"), "(+ a (* b c))");
    assert_eq!(expr_sx("a - b - c"), "(- (- a b) c)");
    assert_eq!(expr_sx("a / b / c"), "(/ (/ a b) c)");
    // RISpec 3.2 Appendix B: `.` binds tighter than `*` and `/`, which bind tighter than `^`.
    assert_eq!(expr_sx("a * b . c"), "(* a (. b c))");
    assert_eq!(expr_sx("a . b * c"), "(* (. a b) c)");
    assert_eq!(expr_sx("a ^ b * c"), "(^ a (* b c))");
    assert_eq!(expr_sx("a ^ b + c"), "(+ (^ a b) c)");
    assert_eq!(expr_sx("a ^ b ^ c"), "(^ (^ a b) c)");
    assert_eq!(expr_sx("L.N"), "(. L N)");
    assert_eq!(expr_sx("-a . b"), "(. (neg a) b)");
    assert_eq!(expr_sx("-a[1]"), "(neg (index a 1))");
    assert_eq!(expr_sx("!a && b || c && d"), "(|| (&& (! a) b) (&& c d))");
    assert_eq!(expr_sx("a < b == c >= d"), "(== (< a b) (>= c d))");
    assert_eq!(expr_sx("a + b < c * d"), "(< (+ a b) (* c d))");
    assert_eq!(expr_sx("a || b ? c : d"), "(? (|| a b) c d)");
    assert_eq!(expr_sx("a ? b : c ? d : e"), "(? a b (? c d e))");
    assert_eq!(expr_sx("x = a ? b : c"), "(= x (? a b c))");
    assert_eq!(expr_sx("a = b = c"), "(= a (= b c))");
    assert_eq!(expr_sx("a += b -= c"), "(+= a (-= b c))");
    assert_eq!(expr_sx("a *= 2"), "(*= a 2)");
    assert_eq!(expr_sx("a /= 2"), "(/= a 2)");
    assert_eq!(expr_sx("a[0] = --b"), "(= (index a 0) (neg (neg b)))");
    assert_eq!(expr_sx("+a"), "a");
    assert_eq!(expr_sx("(a + b) * c"), "(* (+ a b) c)");
}

#[test]
fn numbers_and_strings() {
    assert_eq!(expr_sx("f(1, 1., .5, 1e-3, 1.5E+2)"), "(call f 1 1 0.5 0.001 150)");
    assert_eq!(expr_sx(r#"printf("a\tb\n\\ \"q\"")"#), r#"(call printf "a\tb\n\\ \"q\"")"#);
}

#[test]
fn expression_ids_are_dense_and_unique() {
    let unit = parse_ok(
        "float f(float x = 1) { return -x + 2 * x; }
         surface s(color c = color \"hsv\" (1, 2, 3)) { float a[2] = {1, 2}; if (a[0] > 1) Ci = c; }",
    );
    let mut ids = collect_ids(&unit);
    ids.sort_unstable();
    let expected: Vec<u32> = (0..unit.expr_count).collect();
    assert_eq!(ids, expected);
}

// ---- errors and recovery -------------------------------------------------------------------------

#[test]
fn several_errors_per_run() {
    let (c, r) = errors(
        "surface s() {
            a = 1
            b = 2;
            c = (1, 2);
            d = ;
            e = 4;
        }",
    );
    assert_eq!(c, [codes::SYNTAX, codes::BAD_LITERAL, codes::SYNTAX], "{r}");
}

#[test]
fn rendered_missing_semicolon() {
    let (_, r) = errors("surface s()\n{\n    Ci = Cs\n    Oi = Os;\n}\n");
    let expected = "\
error[E0100]: expected `;` after expression
  ┌─ main.sl:4:5
  │
4 │     Oi = Os;
  │     ^^ found identifier `Oi`

";
    assert_eq!(r, expected);
}

#[test]
fn rendered_unexpected_eof() {
    let (c, r) = errors("surface s() {\n    Ci = 1;\n");
    assert_eq!(c, [codes::UNEXPECTED_EOF]);
    let expected = "\
error[E0101]: unexpected end of file: expected `}`
  ┌─ main.sl:3:1
  │
1 │ surface s() {
  │             - to close this `{`
2 │     Ci = 1;
3 │ 
  │ ^ the file ends here

";
    assert_eq!(r, expected);
}

#[test]
fn rendered_lexer_errors() {
    let (c, r) = errors("surface s() {\n    Ci = 1 @ 2;\n    string x = \"open;\n}\n");
    assert_eq!(c[..2], [codes::BAD_CHAR, codes::UNTERMINATED_STRING]);
    let expected_head = "\
error[E0001]: unexpected character '@'
  ┌─ main.sl:2:12
  │
2 │     Ci = 1 @ 2;
  │            ^ this character cannot start a token

error[E0002]: unterminated string literal
  ┌─ main.sl:3:16
  │
3 │     string x = \"open;
  │                ^^^^^^ this string has no closing `\"` on its line

";
    assert!(r.starts_with(expected_head), "{r}");
}

#[test]
fn rendered_bad_number_and_comment() {
    let (c, r) = errors("surface s() { float x = 1e+; }\n/* never closed\n");
    assert_eq!(c, [codes::BAD_NUMBER, codes::UNTERMINATED_COMMENT], "{r}");
    assert!(r.contains("malformed number `1e+`"));
}

#[test]
fn misc_syntax_errors() {
    for (src, code) in [
        ("float x = 1;", codes::SYNTAX),
        ("surface s(float x) {}", codes::SYNTAX),
        ("surface s() { for (float i = 0; i < 1; i += 1) ; }", codes::SYNTAX),
        ("surface s() { break 0; }", codes::SYNTAX),
        ("surface s() { float a[1.5]; }", codes::SYNTAX),
        ("surface s() { else x = 1; }", codes::SYNTAX),
        ("surface s() { x = void 1; }", codes::SYNTAX),
        ("surface s() { x = (1, 2, 3, 4); }", codes::BAD_LITERAL),
        ("surface s(", codes::UNEXPECTED_EOF),
        ("surface s() { x = f(1, 2 }", codes::SYNTAX),
        ("}", codes::SYNTAX),
        ("surface", codes::UNEXPECTED_EOF),
    ] {
        let (c, r) = errors(src);
        assert_eq!(c.first(), Some(&code), "{src}\n{r}");
    }
}

#[test]
fn deep_nesting_is_an_error_not_a_stack_overflow() {
    let n = 100_000;
    for src in [
        format!("surface s() {{ x = {}1{}; }}", "(".repeat(n), ")".repeat(n)),
        format!("surface s() {{ x = {}1; }}", "-".repeat(n)),
        format!("surface s() {{ x = {}1; }}", "float ".repeat(n)),
        format!("surface s() {}{}", "{".repeat(n), "}".repeat(n)),
        format!("surface s() {{ {} x = 1; }}", "if (1) ".repeat(n)),
        format!("surface s() {{ x = {}1{}; }}", "f(".repeat(n), ")".repeat(n)),
        format!("surface s() {{ x = {}1{}; }}", "{".repeat(n), "}".repeat(n)),
        format!("surface s() {{ x = {}1{}; }}", "a[".repeat(n), "]".repeat(n)),
        format!("surface s() {{ x = {}1; }}", "a ? b : ".repeat(n)),
        format!("surface s() {{ x = {}1; }}", "a = ".repeat(n)),
    ] {
        // A small stack, as in a test thread, must be enough.
        let r = std::thread::Builder::new()
            .stack_size(1 << 20)
            .spawn(move || {
                let (c, _) = errors(&src);
                c
            })
            .unwrap()
            .join()
            .unwrap();
        assert!(r.contains(&codes::SYNTAX), "{r:?}");
        assert!(r.len() <= 3, "{r:?}");
    }
}

// ---- preprocessor --------------------------------------------------------------------------------

#[test]
fn object_and_function_macros() {
    let unit = parse_ok(
        "#define KD 0.5
         #define SQR(x) ((x) * (x))
         #define MIX(a, b, t) ((a) * (1 - (t)) + (b) * (t))
         #define TWICE(x) SQR(x) + SQR(x)
         #define EMPTY
         #define NOARGS() 7
         surface s() { a = KD; b = SQR(a + 1); c = MIX(KD, SQR(2), t); d = TWICE(y) EMPTY; e = NOARGS(); f = SQR; }",
    );
    let got: Vec<String> = body(&unit)
        .iter()
        .map(|s| match &s.kind {
            StmtKind::Expr(e) => sx(e),
            _ => panic!(),
        })
        .collect();
    assert_eq!(
        got,
        [
            "(= a 0.5)",
            "(= b (* (+ a 1) (+ a 1)))",
            "(= c (+ (* 0.5 (- 1 t)) (* (* 2 2) t)))",
            "(= d (+ (* y y) (* y y)))",
            "(= e 7)",
            "(= f SQR)",
        ]
    );
}

#[test]
fn self_referential_macros_terminate() {
    let unit = parse_ok(
        "#define x (x + 1)
         #define f(a) f(a * 2)
         #define A B
         #define B A
         surface s() { y = x; z = f(1); w = A; }",
    );
    let got: Vec<String> = body(&unit)
        .iter()
        .map(|s| match &s.kind {
            StmtKind::Expr(e) => sx(e),
            _ => panic!(),
        })
        .collect();
    assert_eq!(got, ["(= y (+ x 1))", "(= z (call f (* 1 2)))", "(= w A)"]);
}

#[test]
fn stringify_and_paste() {
    let unit = parse_ok(
        "#define STR(x) #x
         #define CAT(a, b) a ## b
         surface s() { printf(STR(hello world)); CAT(fo, o) = CAT(1, 2); }",
    );
    let got: Vec<String> = body(&unit)
        .iter()
        .map(|s| match &s.kind {
            StmtKind::Expr(e) => sx(e),
            _ => panic!(),
        })
        .collect();
    assert_eq!(got, ["(call printf \"hello world\")", "(= foo 12)"]);
}

#[test]
fn macro_argument_count_and_undef() {
    let (c, r) = errors("#define F(a, b) a\nsurface s() { x = F(1); }\n#undef F\nsurface t() { x = F(1); }");
    assert_eq!(c, [codes::MACRO_ARGS], "{r}");
}

#[test]
fn expanded_tokens_point_at_the_macro_use() {
    let (_, diags, sources) = parse_mem("#define BAD 1 +\nsurface s() {\n  x = BAD;\n}\n", &[], &PpOptions::default());
    assert_eq!(diags.items.len(), 1);
    // The error is at `;` after the use; a token from the body would be reported at line 3 too.
    assert_eq!(sources.location(diags.items[0].span), "main.sl:3:10");
    let (_, diags, sources) = parse_mem("#define BAD ) \nsurface s() {\n  x = BAD;\n}\n", &[], &PpOptions::default());
    assert_eq!(sources.location(diags.items[0].span), "main.sl:3:7");
}

#[test]
fn conditionals_nest() {
    let src = "
#define A 2
#if A == 1
  surface one() {}
#elif A == 2
#  ifdef B
     surface two_b() {}
#  else
#    if defined(A) && !defined B && (A * 3 > 5)
       surface two() {}
#    endif
#  endif
#elif 1
  surface three() {}
#else
  surface four() {}
#endif
#ifndef A
  surface five() {}
#else
  surface six() {}
#endif
#if 0
  this ' is skipped, don't @ complain
#endif
";
    let unit = parse_ok(src);
    let names: Vec<&str> = unit
        .items
        .iter()
        .map(|i| match i {
            Item::Shader(s) => s.name.name.as_str(),
            Item::Function(f) => f.name.name.as_str(),
        })
        .collect();
    assert_eq!(names, ["two", "six"]);
}

#[test]
fn command_line_defines() {
    let opts =
        PpOptions { include_dirs: vec![], defines: vec![("QUALITY".into(), Some("3".into())), ("FAST".into(), None)] };
    let (unit, diags, _) =
        parse_mem("#if QUALITY > 2 && FAST == 1\nsurface hi() {}\n#else\nsurface lo() {}\n#endif\n", &[], &opts);
    assert!(!diags.has_errors());
    assert!(matches!(&unit.items[0], Item::Shader(s) if s.name.name == "hi"));
}

#[test]
fn conditional_errors() {
    let (c, _) = errors("#if 1\nsurface s() {}\n");
    assert_eq!(c, [codes::UNBALANCED_CONDITIONAL]);
    let (c, _) = errors("#endif\n#else\n");
    assert_eq!(c, [codes::UNBALANCED_CONDITIONAL, codes::UNBALANCED_CONDITIONAL]);
    let (c, _) = errors("#if 1\n#else\n#else\n#endif\n");
    assert_eq!(c, [codes::UNBALANCED_CONDITIONAL]);
    let (c, _) = errors("#if (1\n#endif\n#frobnicate\n#error stop here, don't go on\n");
    assert_eq!(c, [codes::BAD_DIRECTIVE, codes::BAD_DIRECTIVE, codes::PP_ERROR]);
    let (_, r) = errors("#error stop here\n");
    assert!(r.contains("error[E0015]: stop here"), "{r}");
    // #pragma, #line and a bare # are accepted.
    parse_ok("#pragma once\n#line 10 \"x.sl\"\n#\nsurface s() {}\n");
}

#[test]
fn include_search_order() {
    // "dir/main.sl" includes "a.h": its own directory wins over -I directories, which are
    // searched in order.
    let files = [
        ("dir/a.h", "float from_own_dir() { return 1; }"),
        ("inc1/a.h", "float from_inc1() { return 1; }"),
        ("inc1/b.h", "float b_from_inc1() { return 1; }"),
        ("inc2/b.h", "float b_from_inc2() { return 1; }"),
        ("inc2/c.h", "#include \"b.h\"\nfloat c_from_inc2() { return 1; }"),
    ];
    let map: HashMap<PathBuf, String> = files.iter().map(|(p, t)| (PathBuf::from(p), (*t).to_owned())).collect();
    let mut loader = |p: &Path| map.get(p).cloned();
    let opts = PpOptions { include_dirs: vec!["inc1".into(), "inc2".into()], defines: vec![] };
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let unit = front::parse_source_with(
        &mut sources,
        "dir/main.sl",
        "#include \"a.h\"\n#include <b.h>\n#include \"c.h\"\n",
        &opts,
        &mut loader,
        &mut diags,
    );
    assert!(!diags.has_errors(), "{}", diags.render(&sources));
    let names: Vec<&str> = unit
        .items
        .iter()
        .map(|i| match i {
            Item::Function(f) => f.name.name.as_str(),
            Item::Shader(s) => s.name.name.as_str(),
        })
        .collect();
    // c.h (in inc2) includes "b.h": its own directory inc2 comes before inc1.
    assert_eq!(names, ["from_own_dir", "b_from_inc1", "b_from_inc2", "c_from_inc2"]);
}

#[test]
fn include_errors() {
    let (c, r) = errors("#include \"missing.h\"\nsurface s() {}\n");
    assert_eq!(c, [codes::INCLUDE_NOT_FOUND], "{r}");
    assert!(r.contains("cannot find include file `missing.h`"));
    let (_, diags, _) =
        parse_mem("#include \"self.h\"\n", &[("self.h", "#include \"self.h\"\n")], &PpOptions::default());
    let c: Vec<&str> = diags.items.iter().map(|d| d.code).collect();
    assert_eq!(c, [codes::INCLUDE_DEPTH]);
    // Exponential include trees end too.
    let (_, diags, _) =
        parse_mem("#include \"x.h\"\n", &[("x.h", "#include \"x.h\"\n#include \"x.h\"\n")], &PpOptions::default());
    assert_eq!(diags.items.len(), 1);
    // A guarded header included twice is fine.
    let guarded = "#ifndef G\n#define G\nfloat g() { return 1; }\n#endif\n";
    let (unit, diags, _) =
        parse_mem("#include \"g.h\"\n#include \"g.h\"\n", &[("g.h", guarded)], &PpOptions::default());
    assert!(!diags.has_errors());
    assert_eq!(unit.items.len(), 1);
}

#[test]
fn diagnostics_in_included_files_name_that_file_and_line() {
    let files = [("lib/helpers.h", "// helpers\n\nfloat h() {\n    return 1 +;\n}\n")];
    let opts = PpOptions { include_dirs: vec!["lib".into()], defines: vec![] };
    let (_, diags, sources) = parse_mem("#include \"helpers.h\"\nsurface s() { x = 1 }\n", &files, &opts);
    let locs: Vec<String> = diags.items.iter().map(|d| sources.location(d.span)).collect();
    assert_eq!(locs, ["lib/helpers.h:4:15", "main.sl:2:21"]);
    let r = diags.render(&sources);
    let expected = "\
error[E0100]: expected an expression
  ┌─ lib/helpers.h:4:15
  │
4 │     return 1 +;
  │               ^ found `;`

error[E0100]: expected `;` after expression
  ┌─ main.sl:2:21
  │
2 │ surface s() { x = 1 }
  │                     ^ found `}`

";
    assert_eq!(r, expected);
}

#[test]
fn parse_file_missing_is_a_diagnostic() {
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let unit = front::parse_file(&mut sources, Path::new("/nonexistent/x.sl"), &PpOptions::default(), &mut diags);
    assert!(unit.items.is_empty());
    assert_eq!(diags.items[0].code, codes::INCLUDE_NOT_FOUND);
    assert!(diags.render(&sources).contains("/nonexistent/x.sl"));
}

// ---- the repository's shaders --------------------------------------------------------------------

fn sl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for e in rd.flatten() {
        let p = e.path();
        if p.is_dir() {
            sl_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "sl") {
            out.push(p);
        }
    }
}

/// Every `.sl` file under shaders/rsl and tests/data/rsl/conformance parses without errors
/// (tests/data/rsl/diagnostics holds files that are meant to fail).
#[test]
fn repository_shaders_parse() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    sl_files(&root.join("shaders/rsl"), &mut files);
    sl_files(&root.join("tests/data/rsl/conformance"), &mut files);
    files.sort();
    let mut failures = String::new();
    for f in &files {
        let opts = PpOptions {
            include_dirs: vec![root.join("shaders/rsl/include"), root.join("tests/data/rsl/include")],
            defines: vec![],
        };
        let mut sources = SourceMap::new();
        let mut diags = Diagnostics::new();
        let _ = front::parse_file(&mut sources, f, &opts, &mut diags);
        if diags.has_errors() {
            failures.push_str(&diags.render(&sources));
        }
    }
    assert!(failures.is_empty(), "{failures}");
}

/// The files in tests/data/rsl/diagnostics never crash the front end.
#[test]
fn diagnostic_files_do_not_panic() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    sl_files(&root.join("tests/data/rsl/diagnostics"), &mut files);
    for f in &files {
        let mut sources = SourceMap::new();
        let mut diags = Diagnostics::new();
        let _ = front::parse_file(&mut sources, f, &PpOptions::default(), &mut diags);
        let _ = diags.render(&sources);
    }
}

// ---- never panic, always end ---------------------------------------------------------------------

const PIECES: &[&str] = &[
    "surface",
    "light",
    "float",
    "color",
    "point",
    "matrix",
    "string",
    "void",
    "uniform",
    "varying",
    "output",
    "extern",
    "if",
    "else",
    "while",
    "for",
    "break",
    "continue",
    "return",
    "illuminance",
    "illuminate",
    "solar",
    "gather",
    "x",
    "f",
    "Ci",
    "1",
    ".5",
    "1e3",
    "\"s\"",
    "+",
    "-",
    "*",
    "/",
    "^",
    ".",
    "==",
    "!=",
    "<",
    ">=",
    "&&",
    "||",
    "!",
    "?",
    ":",
    "=",
    "+=",
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    ",",
    ";",
    "\n#define X",
    "\n#define F(a) a a",
    "X",
    "F",
    "\n#if 1\n",
    "\n#if\n",
    "\n#else\n",
    "\n#endif\n",
    "\n#include \"x.h\"\n",
    "#",
    "##",
    "\n#undef X\n",
    "/*",
    "*/",
    "//",
    "\"",
    "@",
    "\\\n",
];

fn no_files(_: &Path) -> Option<String> {
    None
}

fn run_front_end(src: &str) {
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    let mut loader = no_files;
    let _ = front::parse_source_with(&mut sources, "fuzz.sl", src, &PpOptions::default(), &mut loader, &mut diags);
    let _ = diags.render(&sources);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn random_token_streams_never_panic(toks in prop::collection::vec(prop::sample::select(PIECES), 0..200)) {
        run_front_end(&toks.join(" "));
    }

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        run_front_end(&String::from_utf8_lossy(&bytes));
    }

    /// Valid shaders with one token deleted still terminate and report errors, not panics.
    #[test]
    fn mutilated_shaders_never_panic(cut in 0usize..400) {
        let src = "surface s(float Ka = 1, Kd = .5; color c = 1;) {
            normal Nf = faceforward(normalize(N), I);
            illuminance(\"spec\", P, Nf, PI/2) { Ci += Cl * (Nf . normalize(L)); }
            for (i = 0; i < 3; i += 1) { if (i > 1) break; else continue; }
            Ci = color \"hsv\" (1, 0.5, c[0]) * (Ka > 0 ? Ka : Kd);
        }";
        let toks: Vec<&str> = src.split_whitespace().collect();
        let n = toks.len();
        let kept: Vec<&str> = toks.iter().enumerate().filter(|(i, _)| *i != cut % n).map(|(_, t)| *t).collect();
        run_front_end(&kept.join(" "));
    }
}

#[test]
fn exponential_macros_end_with_a_diagnostic() {
    let mut src = String::from("#define M0 x x\n");
    for i in 1..40 {
        let _ = writeln!(src, "#define M{i} M{} M{}", i - 1, i - 1);
    }
    src.push_str("surface s() { M39; }\n");
    let (c, _) = errors(&src);
    assert!(c.contains(&codes::PP_ERROR), "{c:?}");
    let (c, _) = errors(&format!("#define F(x) x\nsurface s() {{ y = {}1{}; }}", "F(".repeat(5000), ")".repeat(5000)));
    assert!(c.contains(&codes::PP_ERROR), "{c:?}");
}
