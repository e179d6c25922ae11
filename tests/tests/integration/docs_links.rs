//! Every relative link in the repository's Markdown files (`[text](path)`, `[text](path#anchor)`)
//! names a file or directory that exists, and every anchor into a Markdown file names one of
//! its headings.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn markdown_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    for e in rd.flatten() {
        let p = e.path();
        let name = e.file_name().to_string_lossy().into_owned();
        if p.is_dir() {
            if !name.starts_with('.') && name != "target" && name != "fuzz" {
                markdown_files(&p, out);
            }
        } else if name.ends_with(".md") {
            out.push(p);
        }
    }
}

/// The targets of the inline links of `text` (not inside code spans or fenced blocks).
fn links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        // Drop code spans.
        let mut plain = String::new();
        let mut in_code = false;
        for c in line.chars() {
            if c == '`' {
                in_code = !in_code;
            } else if !in_code {
                plain.push(c);
            }
        }
        let b = plain.as_bytes();
        let mut i = 0;
        while let Some(k) = plain[i..].find("](") {
            let start = i + k + 2;
            let Some(end) = plain[start..].find(')') else { break };
            let target = plain[start..start + end].trim();
            if !target.is_empty() && b[start] != b'<' {
                out.push(target.to_string());
            }
            i = start + end;
        }
    }
    out
}

/// GitHub's anchor of a heading: lower case, spaces to `-`, punctuation dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

#[test]
fn relative_links_in_markdown_resolve() {
    let mut files = Vec::new();
    markdown_files(&root(), &mut files);
    assert!(files.len() >= 10, "found only {} Markdown files", files.len());
    let mut dead = Vec::new();
    let mut checked = 0;
    for f in &files {
        let text = std::fs::read_to_string(f).expect("readable");
        for l in links(&text) {
            if l.contains("://") || l.starts_with("mailto:") {
                continue;
            }
            let (path, frag) = match l.split_once('#') {
                Some((p, a)) => (p, Some(a)),
                None => (l.as_str(), None),
            };
            let target = if path.is_empty() { f.clone() } else { f.parent().expect("a directory").join(path) };
            checked += 1;
            if !target.exists() {
                dead.push(format!("{}: {l}", f.strip_prefix(root()).unwrap_or(f).display()));
                continue;
            }
            if let (Some(frag), true) = (frag, target.extension().is_some_and(|x| x == "md")) {
                let body = std::fs::read_to_string(&target).unwrap_or_default();
                let found =
                    body.lines().filter_map(|h| h.strip_prefix('#')).any(|h| anchor(h.trim_start_matches('#')) == frag);
                if !found {
                    dead.push(format!("{}: {l} (no such heading)", f.strip_prefix(root()).unwrap_or(f).display()));
                }
            }
        }
    }
    assert!(checked >= 20, "only {checked} relative links checked");
    assert!(dead.is_empty(), "{} dead links:\n{}", dead.len(), dead.join("\n"));
}

#[test]
fn link_extraction_and_anchors() {
    let t =
        "see [a](docs/x.md#the-y), `[not](code.md)`, [b](../c.rs) and [web](https://e.org)\n```\n[no](fenced.md)\n```";
    assert_eq!(links(t), vec!["docs/x.md#the-y", "../c.rs", "https://e.org"]);
    assert_eq!(anchor(" The `y`, and Z!"), "the-y-and-z");
}
