//! The reader never panics and always finishes: random token streams and random byte mutations
//! of a valid file.

use anysl_rib::{parse_bytes, Options, Recorder, Request};
use proptest::prelude::*;

const NAMES: &[&str] = &[
    "WorldBegin",
    "WorldEnd",
    "FrameBegin",
    "FrameEnd",
    "AttributeBegin",
    "AttributeEnd",
    "TransformBegin",
    "TransformEnd",
    "SolidBegin",
    "SolidEnd",
    "ObjectBegin",
    "ObjectEnd",
    "ObjectInstance",
    "MotionBegin",
    "MotionEnd",
    "ArchiveBegin",
    "ArchiveEnd",
    "ReadArchive",
    "Declare",
    "Option",
    "Attribute",
    "Sphere",
    "Polygon",
    "PointsPolygons",
    "PointsGeneralPolygons",
    "NuPatch",
    "TrimCurve",
    "Basis",
    "Color",
    "Transform",
    "Skew",
    "LightSource",
    "Illuminate",
    "Surface",
    "Display",
    "Projection",
    "Format",
    "SubdivisionMesh",
    "Blobby",
    "Procedural",
    "MakeCubeFaceEnvironment",
    "DepthOfField",
    "Curves",
    "version",
    "Unknown",
];

const STRINGS: &[&str] = &[
    "\"P\"",
    "\"Cs\"",
    "\"st\"",
    "\"a\"",
    "\"searchpath\"",
    "\"archive\"",
    "\"shader\"",
    "\"@:&:/x\"",
    "\"uniform float Ks\"",
    "\"vertex point Q\"",
    "\"float[2] f\"",
    "\"integer n\"",
    "\"string s\"",
    "\"bogus decl x\"",
    "\"color\"",
    "\"bezier\"",
    "\"\\101\\\"\"",
    "\"",
    "\"unterminated\n",
];

fn token() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => prop::sample::select(NAMES).prop_map(str::to_owned),
        3 => any::<i16>().prop_map(|i| i.to_string()),
        2 => any::<f32>().prop_map(|f| format!("{f:e}")),
        3 => prop::sample::select(STRINGS).prop_map(str::to_owned),
        2 => Just("[".to_owned()),
        2 => Just("]".to_owned()),
        1 => prop::sample::select(&["#c\n", "\n", "@", "1.2.3", "-", ".", "\u{e9}", "\\", "\0"][..]).prop_map(str::to_owned),
    ]
}

const VALID: &str = "##RenderMan RIB\nversion 3.03\nDeclare \"Kc\" \"uniform color\"\n\
Option \"searchpath\" \"shader\" [\"/s:@\"]\nFormat 320 240 1\nProjection \"perspective\" \"fov\" [40]\n\
ArchiveBegin \"leaf\" Sphere 0.1 -0.1 0.1 360 ArchiveEnd\nFrameBegin 1\nWorldBegin\n\
LightSource \"pointlight\" 1 \"from\" [0 4 0] \"intensity\" 12\nAttributeBegin\n\
  Color [1 0.5 0.2]\n  Surface \"plastic\" \"Ks\" [0.5] \"Kc\" [1 1 1]\n  Translate 0 0 5\n\
  PointsPolygons [3 3] [0 1 2 0 2 3] \"P\" [0 0 0 1 0 0 1 1 0 0 1 0] \"st\" [0 0 1 0 1 1 0 1]\n\
  ReadArchive \"leaf\"\n  Basis \"bezier\" 3 \"bezier\" 3\nAttributeEnd\nWorldEnd\nFrameEnd\n";

fn options() -> Options {
    Options { max_requests: 2_000, ..Options::default() }
}

/// Reads `bytes`; checks the invariants that hold whatever the input.
fn read(bytes: &[u8]) {
    let mut r = Recorder::new();
    match parse_bytes("fuzz.rib", bytes, &mut r, &options()) {
        Ok(report) => {
            assert!(report.warnings.iter().all(|d| !d.is_error()));
            let _ = report.render_warnings();
        }
        Err(e) => {
            assert!(e.errors().count() > 0);
            let text = e.render();
            assert!(text.contains("error["), "{text}");
        }
    }
    for req in &r.requests {
        // Every location lies inside its file.
        let loc = req.loc();
        assert!(loc.start <= loc.end && loc.line >= 1 && loc.col >= 1);
        let _: &Request = req;
    }
}

#[test]
fn the_valid_file_reads() {
    let mut r = Recorder::new();
    parse_bytes("valid.rib", VALID.as_bytes(), &mut r, &options()).unwrap();
    assert_eq!(r.requests.len(), 16);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2048, ..ProptestConfig::default() })]

    #[test]
    fn random_token_streams(tokens in prop::collection::vec(token(), 0..80), seps in prop::collection::vec(prop::sample::select(&[" ", "\n", "", "\t"][..]), 80)) {
        let mut text = String::new();
        for (t, s) in tokens.iter().zip(&seps) {
            text.push_str(t);
            text.push_str(s);
        }
        read(text.as_bytes());
    }

    #[test]
    fn random_byte_mutations(edits in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>(), 0..3u8), 1..12)) {
        let mut bytes = VALID.as_bytes().to_vec();
        for (at, byte, op) in edits {
            let i = at.index(bytes.len() + 1);
            match op {
                0 if i < bytes.len() => bytes[i] = byte,
                1 => bytes.insert(i, byte),
                _ if i < bytes.len() => { bytes.remove(i); }
                _ => bytes.push(byte),
            }
        }
        read(&bytes);
    }

    #[test]
    fn random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..256)) {
        read(&bytes);
    }
}
