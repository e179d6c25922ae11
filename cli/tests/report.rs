//! `anysl report --quick` writes a page with every section.

use std::process::Command;

#[test]
fn quick_report_has_every_section() {
    let out = std::env::temp_dir().join(format!("anysl-report-test-{}", std::process::id()));
    let run = Command::new(env!("CARGO_BIN_EXE_anysl"))
        .args(["report", "--quick", "--out"])
        .arg(&out)
        .output()
        .expect("the anysl binary runs");
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "report failed:\n{stdout}\n{}", String::from_utf8_lossy(&run.stderr));
    let index = out.join("index.html");
    assert!(stdout.contains(&format!("report written to {}", index.display())), "{stdout}");
    let html = std::fs::read_to_string(&index).expect("index.html");
    for id in ["table1", "accuracy", "antialias", "intervals", "leave-out", "stability"] {
        assert!(html.contains(&format!("<section id=\"{id}\">")), "section {id} missing");
    }
    assert!(html.matches("<svg").count() >= 10 + 6, "a plot per shader (b) and per AA shader (c)");
    assert!(html.contains("data:image/png;base64,"), "inline pictures");
    assert!(!html.contains("FAIL"), "a check failed:\n{html}");
    assert!(std::fs::read_to_string(out.join("summary.txt")).is_ok_and(|s| s.contains("stability cases pass")));
    let _ = std::fs::remove_dir_all(&out);
}
