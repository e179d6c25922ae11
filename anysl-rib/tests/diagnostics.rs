//! Diagnostics, compared as exact rendered text.

mod util;

use anysl_rib::{codes, parse_bytes, parse_str, BuildError, Loc, Options, ParamList, Recorder, RibBuilder};

/// Renders what reading `text` reports (errors, or the warnings of a successful read).
fn render(text: &[u8]) -> String {
    let mut r = Recorder::new();
    match parse_bytes("scene.rib", text, &mut r, &Options::default()) {
        Ok(rep) => rep.render_warnings(),
        Err(e) => e.render(),
    }
}

/// Compares rendered text, showing both in full on a difference.
fn assert_text(got: &str, expected: &str) {
    assert!(got == expected, "rendered:\n{got}\nexpected:\n{expected}");
}

#[test]
fn bad_token() {
    assert_text(
        &render(b"WorldBegin\nSphere 1 -1 1 360 @\nWorldEnd\n"),
        "\
error[R001]: unexpected character `@`
  --> scene.rib:2:19
  |
2 | Sphere 1 -1 1 360 @
  |                   ^

",
    );
}

#[test]
fn malformed_number() {
    assert_text(
        &render(b"Translate 1.2.3 0 0\n"),
        "\
error[R003]: malformed number `1.2.3`
  --> scene.rib:1:11
  |
1 | Translate 1.2.3 0 0
  |           ^^^^^

",
    );
}

#[test]
fn unterminated_string() {
    assert_text(
        &render(b"Surface \"plastic\nWorldBegin\n"),
        "\
error[R002]: unterminated string
  --> scene.rib:1:9
  |
1 | Surface \"plastic
  |         ^^^^^^^^
  |
  = the string opened here has no closing `\"` before the end of the file

",
    );
}

#[test]
fn wrong_argument_count() {
    assert_text(
        &render(b"WorldBegin\nSphere 1 -1\nWorldEnd\n"),
        "\
error[R021]: not enough arguments for `Sphere`
  --> scene.rib:2:1
  |
2 | Sphere 1 -1
  | ^^^^^^^^^^^ `zmax` is missing (2 values given)
  |
  = usage: Sphere radius zmin zmax thetamax params

",
    );
}

#[test]
fn wrong_array_length() {
    assert_text(
        &render(b"Color [1 0]\n"),
        "\
error[R021]: `Color` expects 3 numbers for `rgb`, the array has 2
  --> scene.rib:1:7
  |
1 | Color [1 0]
  |       ^^^^^ expected 3 numbers
  |
  = usage: Color rgb

",
    );
}

#[test]
fn wrong_type() {
    assert_text(
        &render(b"Translate 1 \"two\" 3\n"),
        "\
error[R022]: `Translate` expects a number for `dy`, found the string \"two\"
  --> scene.rib:1:13
  |
1 | Translate 1 \"two\" 3
  |             ^^^^^ expected a number
  |
  = usage: Translate dx dy dz

",
    );
}

#[test]
fn unbalanced_attribute_end() {
    assert_text(
        &render(b"WorldBegin\nAttributeEnd\nWorldEnd\n"),
        "\
error[R040]: `AttributeEnd` without `AttributeBegin`
  --> scene.rib:2:1
  |
2 | AttributeEnd
  | ^^^^^^^^^^^^ no `AttributeBegin` is open

",
    );
    assert_text(
        &render(b"AttributeBegin\nTransformBegin\nAttributeEnd\n"),
        "\
error[R040]: `AttributeEnd` does not match the open `TransformBegin`
  --> scene.rib:3:1
  |
2 | TransformBegin
  | -------------- `TransformBegin` opened here
3 | AttributeEnd
  | ^^^^^^^^^^^^ expected `TransformEnd`

",
    );
}

#[test]
fn unclosed_block() {
    assert_text(
        &render(b"WorldBegin\nSphere 1 -1 1 360\n"),
        "\
error[R041]: `WorldBegin` is never closed
  --> scene.rib:1:1
  |
1 | WorldBegin
  | ^^^^^^^^^^ opened here
  |
  = add `WorldEnd` after the last request of the block

",
    );
}

#[test]
fn value_count_mismatch() {
    assert_text(
        &render(b"Polygon \"P\" [0 0 0 1 1 1 2]\n"),
        "\
error[R032]: parameter \"P\" (vertex point) has 7 values, not a multiple of 3
  --> scene.rib:1:13
  |
1 | Polygon \"P\" [0 0 0 1 1 1 2]
  |             ^^^^^^^^^^^^^^^ 7 values
  |
  = each point takes 3 values

",
    );
}

#[test]
fn brackets() {
    assert_text(
        &render(b"Translate 1 2 3 ]\nColor [1 0 0\nSphere 1 -1 1 360\n"),
        "\
error[R010]: `]` without `[`
  --> scene.rib:1:17
  |
1 | Translate 1 2 3 ]
  |                 ^ unmatched `]`

error[R011]: `[` without `]`
  --> scene.rib:2:7
  |
2 | Color [1 0 0
  |       ^ this array is not closed
  |
  = close the array with `]` before the next request

",
    );
}

#[test]
fn binary_rib() {
    assert_text(
        &render(b"Sphere 1 -1 1 360\n\x92\x01\x02"),
        "\
error[R004]: binary RIB is not supported
  --> scene.rib:2:1
  |
2 | ?\u{1}\u{2}
  | ^
  |
  = convert the file to ASCII RIB (e.g. `catrib` or `prman -catrib`)

",
    );
}

#[test]
fn several_errors_per_run_and_recovery() {
    let mut r = Recorder::new();
    let e = parse_str(
        "scene.rib",
        "Translate 1 2\nSphere 1 -1 1 360\nRotate \"x\" 0 0 1\nScale 1 1 1 1\nDisk 0 1 360\n",
        &mut r,
        &Options::default(),
    )
    .unwrap_err();
    let codes: Vec<_> = e.errors().map(|d| (d.code, d.loc.line)).collect();
    assert_eq!(codes, [(codes::ARG_COUNT, 1), (codes::ARG_TYPE, 3), (codes::EXTRA_ARGS, 4)]);
    let names: Vec<_> = r.requests.iter().map(|r| r.name()).collect();
    assert_eq!(names, ["Sphere", "Disk"], "good requests between bad ones still reach the builder");
}

#[test]
fn values_before_any_request() {
    assert_text(
        &render(b"1 2 3 Sphere 1 -1 1 360\n"),
        "\
error[R020]: expected a request name
  --> scene.rib:1:1
  |
1 | 1 2 3 Sphere 1 -1 1 360
  | ^ this value belongs to no request

",
    );
}

#[test]
fn error_limit_stops_reading() {
    let text = "Sphere\n".repeat(10);
    let options = Options { max_errors: 3, ..Options::default() };
    let e = parse_str("x.rib", &text, &mut Recorder::new(), &options).unwrap_err();
    let codes: Vec<_> = e.errors().map(|d| d.code).collect();
    assert_eq!(codes, [codes::ARG_COUNT, codes::ARG_COUNT, codes::ARG_COUNT, codes::LIMIT]);
}

/// A builder that supports spheres only and refuses negative radii.
struct Picky;

impl RibBuilder for Picky {
    fn sphere(&mut self, _: &Loc, radius: f32, _: f32, _: f32, _: f32, _: &ParamList) -> Result<(), BuildError> {
        if radius < 0.0 {
            return Err(BuildError::error("negative sphere radius").with_note("use a positive radius"));
        }
        if radius == 0.0 {
            return Err(BuildError::warning("empty sphere"));
        }
        Ok(())
    }
}

#[test]
fn unknown_and_unsupported_requests_warn_once_per_name() {
    let text = b"Frobnicate 1 2 [3]\nSphere 1 -1 1 360\nDisk 0 1 360\nDisk 0 2 360\nFrobnicate\nDisk 0 3 360\n";
    let report = parse_bytes("scene.rib", text, &mut Picky, &Options::default()).unwrap();
    assert_text(
        &report.render_warnings(),
        "\
warning[W001]: unknown request `Frobnicate`
  --> scene.rib:1:1
  |
1 | Frobnicate 1 2 [3]
  | ^^^^^^^^^^ skipped with its arguments

warning[W002]: unsupported request `Disk` (ignored)
  --> scene.rib:3:1
  |
3 | Disk 0 1 360
  | ^^^^ not supported by this builder
  |
  = `Disk` appears 3 times; only the first is shown

",
    );
}

#[test]
fn builder_errors_and_warnings_come_back_with_the_location() {
    let e = parse_bytes(
        "scene.rib",
        b"Sphere 1 -1 1 360\n  Sphere -1 -1 1 360\nSphere 0 0 0 360\n",
        &mut Picky,
        &Options::default(),
    )
    .unwrap_err();
    assert_text(
        &e.render(),
        "\
error[R060]: negative sphere radius
  --> scene.rib:2:3
  |
2 |   Sphere -1 -1 1 360
  |   ^^^^^^ in `Sphere`
  |
  = use a positive radius

warning[W004]: empty sphere
  --> scene.rib:3:1
  |
3 | Sphere 0 0 0 360
  | ^^^^^^ in `Sphere`

",
    );
}

#[test]
fn undeclared_parameter_warning() {
    assert_text(
        &render(b"Surface \"wood\" \"grain\" [3]\n"),
        "\
warning[W003]: undeclared parameter \"grain\"
  --> scene.rib:1:16
  |
1 | Surface \"wood\" \"grain\" [3]
  |                ^^^^^^^ taken as `uniform float`
  |
  = declare it inline (\"uniform color grain\") or with `Declare \"grain\" \"…\"`

",
    );
}

#[test]
fn diagnostic_display_is_one_line() {
    let e = parse_str("a.rib", "Sphere 1", &mut Recorder::new(), &Options::default()).unwrap_err();
    let d = e.errors().next().unwrap();
    assert_eq!(d.to_string(), "a.rib:1:1: error[R021]: not enough arguments for `Sphere`");
}
