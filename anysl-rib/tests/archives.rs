//! `ReadArchive`, search paths with `@` and `&`, inline archives, gzip, include cycles.

mod util;

use anysl_rib::{codes, parse_bytes, parse_file, Options, Recorder, Request, SearchPaths};
use std::io::Write as _;
use std::path::PathBuf;
use util::{show, TempDir};

fn read(path: &std::path::Path, options: &Options) -> (Vec<Request>, anysl_rib::Report) {
    let mut r = Recorder::new();
    match parse_file(path, &mut r, options) {
        Ok(rep) => (r.requests, rep),
        Err(e) => panic!("{}", e.render()),
    }
}

fn names(reqs: &[Request]) -> Vec<String> {
    reqs.iter().map(show).collect()
}

fn gzip(text: &str) -> Vec<u8> {
    let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    e.write_all(text.as_bytes()).unwrap();
    e.finish().unwrap()
}

#[test]
fn read_archive_relative_to_the_including_file() {
    let dir = TempDir::new("rel");
    let main = dir.write("scene/main.rib", "WorldBegin\nReadArchive \"parts/a.rib\"\nWorldEnd\n");
    dir.write("scene/parts/a.rib", "Translate 1 0 0\nReadArchive \"b.rib\"\n");
    dir.write("scene/parts/b.rib", "Sphere 1 -1 1 360\n");
    let (reqs, _) = read(&main, &Options::default());
    let shown = names(&reqs);
    assert_eq!(shown[1], "Translate { dx: 1.0, dy: 0.0, dz: 0.0 }");
    assert_eq!(reqs[2].name(), "Sphere");
    // Locations name the archive they come from.
    assert!(reqs[2].loc().name.ends_with("b.rib"), "{}", reqs[2].loc());
    assert_eq!(reqs[2].loc().line, 1);
}

#[test]
fn archive_search_path_with_default_and_previous() {
    let dir = TempDir::new("search");
    let lib1 = dir.0.join("lib1");
    let lib2 = dir.0.join("lib2");
    let deflib = dir.0.join("default");
    dir.write("lib1/one.rib", "Translate 1 1 1\n");
    dir.write("lib2/two.rib", "Scale 2 2 2\n");
    dir.write("default/three.rib", "Rotate 3 0 0 1\n");
    let main = dir.write(
        "main.rib",
        format!(
            "Option \"searchpath\" \"archive\" [\"{}\"]\n\
             Option \"searchpath\" \"archive\" [\"{}:&:@\"]\n\
             ReadArchive \"one.rib\"\nReadArchive \"two.rib\"\nReadArchive \"three.rib\"\n\
             Option \"searchpath\" \"shader\" [\"/my/shaders:@\"] \"texture\" \"&:/tex\"\n",
            lib1.display(),
            lib2.display()
        ),
    );
    let options = Options::default().with_search_paths(
        SearchPaths::new().with("archive", vec![deflib.clone()]).with("shader", vec![PathBuf::from("/std/shaders")]),
    );
    let (reqs, report) = read(&main, &options);
    let shown = names(&reqs);
    assert!(shown.contains(&"Translate { dx: 1.0, dy: 1.0, dz: 1.0 }".to_string()), "{shown:?}");
    assert!(shown.contains(&"Scale { sx: 2.0, sy: 2.0, sz: 2.0 }".to_string()), "{shown:?}");
    assert!(shown.contains(&"Rotate { angle: 3.0, dx: 0.0, dy: 0.0, dz: 1.0 }".to_string()), "{shown:?}");
    assert_eq!(report.search_paths.get("archive"), [lib2, lib1, deflib]);
    assert_eq!(report.search_paths.get("shader"), [PathBuf::from("/my/shaders"), PathBuf::from("/std/shaders")]);
    assert_eq!(report.search_paths.get("texture"), [PathBuf::from("/tex")]);
    // The builder saw each change.
    let kinds: Vec<&str> = reqs
        .iter()
        .filter_map(|r| match r {
            Request::SearchPath { kind, .. } => Some(kind.as_str()),
            _ => None,
        })
        .collect();
    assert_eq!(kinds, ["archive", "archive", "shader", "texture"]);
}

#[test]
fn search_paths_start_from_the_defaults() {
    let mut r = Recorder::new();
    let options = Options::default().with_search_paths(SearchPaths::new().with("shader", vec![PathBuf::from("/d")]));
    let report = parse_bytes("x.rib", b"Option \"searchpath\" \"shader\" \"/a:&\"", &mut r, &options).unwrap();
    assert_eq!(report.search_paths.get("shader"), [PathBuf::from("/a"), PathBuf::from("/d")]);
}

#[test]
fn gzip_is_detected_by_content() {
    let dir = TempDir::new("gz");
    dir.write("part.rib", gzip("Sphere 2 -2 2 360\n"));
    let main = dir.write("main.rib.z", gzip("WorldBegin\nReadArchive \"part.rib\"\nWorldEnd\n"));
    let (reqs, _) = read(&main, &Options::default());
    assert_eq!(reqs.iter().map(Request::name).collect::<Vec<_>>(), ["WorldBegin", "Sphere", "WorldEnd"]);
    let mut r = Recorder::new();
    parse_bytes("mem.rib", &gzip("Translate 1 2 3"), &mut r, &Options::default()).unwrap();
    assert_eq!(show(&r.requests[0]), "Translate { dx: 1.0, dy: 2.0, dz: 3.0 }");
}

#[test]
fn corrupt_gzip_is_an_error() {
    let mut bytes = gzip("Translate 1 2 3 Translate 1 2 3 Translate 1 2 3");
    bytes.truncate(12);
    let e = parse_bytes("bad.rib.gz", &bytes, &mut Recorder::new(), &Options::default()).unwrap_err();
    assert_eq!(e.errors().map(|d| d.code).collect::<Vec<_>>(), [codes::IO]);
}

#[test]
fn include_cycles_are_errors() {
    let dir = TempDir::new("cycle");
    let main = dir.write("main.rib", "Translate 0 0 0\nReadArchive \"a.rib\"\nScale 1 1 1\n");
    dir.write("a.rib", "ReadArchive \"b.rib\"\n");
    dir.write("b.rib", "Sphere 1 -1 1 360\nReadArchive \"main.rib\"\n");
    let mut r = Recorder::new();
    let e = parse_file(&main, &mut r, &Options::default()).unwrap_err();
    let errs: Vec<_> = e.errors().collect();
    assert_eq!(errs.len(), 1);
    assert_eq!(errs[0].code, codes::INCLUDE_CYCLE);
    assert_eq!(errs[0].secondary.len(), 2, "the chain a.rib → b.rib is shown");
    // Reading went on around the cycle.
    assert_eq!(r.requests.iter().map(Request::name).collect::<Vec<_>>(), ["Translate", "Sphere", "Scale"]);

    let selfref = dir.write("self.rib", "ReadArchive \"self.rib\"\n");
    let e = parse_file(&selfref, &mut Recorder::new(), &Options::default()).unwrap_err();
    assert_eq!(e.errors().map(|d| d.code).collect::<Vec<_>>(), [codes::INCLUDE_CYCLE]);
}

#[test]
fn missing_archive_lists_where_it_looked() {
    let dir = TempDir::new("missing");
    let main =
        dir.write("main.rib", "Option \"searchpath\" \"archive\" \"/nonexistent/lib\"\nReadArchive \"nope.rib\"\n");
    let e = parse_file(&main, &mut Recorder::new(), &Options::default()).unwrap_err();
    let d = e.errors().next().unwrap();
    assert_eq!(d.code, codes::ARCHIVE_NOT_FOUND);
    assert!(d.notes[0].contains("/nonexistent/lib/nope.rib"), "{:?}", d.notes);
    assert_eq!(d.loc.line, 2);
}

#[test]
fn missing_top_level_file_is_an_error() {
    let e = parse_file("/nonexistent/scene.rib", &mut Recorder::new(), &Options::default()).unwrap_err();
    assert_eq!(e.errors().map(|d| d.code).collect::<Vec<_>>(), [codes::IO]);
}

#[test]
fn inline_archives_are_replayed() {
    let text = "ArchiveBegin \"leaf\"\n  Sphere 0.1 -0.1 0.1 360\n  ArchiveBegin \"inner\" Disk 0 1 360 ArchiveEnd\nArchiveEnd\n\
                WorldBegin\nReadArchive \"leaf\"\nTranslate 1 0 0\nReadArchive \"leaf\"\nReadArchive \"inner\"\nWorldEnd\n";
    let mut r = Recorder::new();
    parse_bytes("inline.rib", text.as_bytes(), &mut r, &Options::default()).unwrap();
    let n: Vec<&str> = r.requests.iter().map(Request::name).collect();
    assert_eq!(n, ["WorldBegin", "Sphere", "Translate", "Sphere", "Disk", "WorldEnd"]);
    // Replayed requests keep their place in the file.
    assert_eq!(r.requests[1].loc().line, 2);
}

#[test]
fn inline_archive_cycles_and_errors() {
    let e = parse_bytes(
        "x.rib",
        b"ArchiveBegin \"a\" ReadArchive \"a\" ArchiveEnd ReadArchive \"a\"",
        &mut Recorder::new(),
        &Options::default(),
    )
    .unwrap_err();
    assert_eq!(e.errors().map(|d| d.code).collect::<Vec<_>>(), [codes::INCLUDE_CYCLE]);
    let e = parse_bytes("x.rib", b"ArchiveBegin \"a\" Sphere 1 -1 1 360", &mut Recorder::new(), &Options::default())
        .unwrap_err();
    assert_eq!(e.errors().map(|d| d.code).collect::<Vec<_>>(), [codes::UNCLOSED_ARCHIVE]);
    let e = parse_bytes("x.rib", b"ArchiveEnd", &mut Recorder::new(), &Options::default()).unwrap_err();
    assert_eq!(e.errors().map(|d| d.code).collect::<Vec<_>>(), [codes::UNBALANCED_END]);
    // An error inside an archive replayed twice is reported once.
    let e = parse_bytes(
        "x.rib",
        b"ArchiveBegin \"a\" Sphere 1 ArchiveEnd ReadArchive \"a\" ReadArchive \"a\"",
        &mut Recorder::new(),
        &Options::default(),
    )
    .unwrap_err();
    assert_eq!(e.errors().map(|d| d.code).collect::<Vec<_>>(), [codes::ARG_COUNT]);
}

#[test]
fn request_budget_stops_runaway_archives() {
    // Each archive reads the previous one twice: 2^30 spheres without a budget.
    let mut text = String::from("ArchiveBegin \"a0\" Sphere 1 -1 1 360 ArchiveEnd\n");
    for i in 1..=30 {
        text.push_str(&format!(
            "ArchiveBegin \"a{i}\" ReadArchive \"a{}\" ReadArchive \"a{}\" ArchiveEnd\n",
            i - 1,
            i - 1
        ));
    }
    text.push_str("ReadArchive \"a30\"\n");
    let options = Options { max_requests: 10_000, ..Options::default() };
    let e = parse_bytes("bomb.rib", text.as_bytes(), &mut Recorder::new(), &options).unwrap_err();
    assert_eq!(e.errors().map(|d| d.code).collect::<Vec<_>>(), [codes::LIMIT]);
}

#[test]
fn same_archive_read_twice_is_loaded_once() {
    let dir = TempDir::new("twice");
    dir.write("p.rib", "Sphere 1 -1 1 360\n");
    let main = dir.write("main.rib", "ReadArchive \"p.rib\"\nReadArchive \"p.rib\"\n");
    let (reqs, report) = read(&main, &Options::default());
    assert_eq!(reqs.len(), 2);
    assert_eq!(report.sources.files().len(), 2);
}
