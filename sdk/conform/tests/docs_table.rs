//! docs/conformance.md's table of checks is generated from the catalogue
//! ([`jaus_conform::catalogue::markdown`]): this test fails when the two differ, and
//! rewrites the docs when `UPDATE_DOCS=1` is set.

use std::path::PathBuf;

const BEGIN: &str = "<!-- checks:begin -->";
const END: &str = "<!-- checks:end -->";

fn docs() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/conformance.md")
}

/// The docs with the text between the markers replaced by `table`.
fn with_table(docs: &str, table: &str) -> String {
    let begin = docs
        .find(BEGIN)
        .unwrap_or_else(|| panic!("docs/conformance.md has no {BEGIN}"));
    let end = docs
        .find(END)
        .unwrap_or_else(|| panic!("docs/conformance.md has no {END}"));
    assert!(begin < end, "{BEGIN} after {END} in docs/conformance.md");
    format!("{}{BEGIN}\n{table}{}", &docs[..begin], &docs[end..])
}

#[test]
fn the_docs_table_is_the_catalogue() {
    let spec = jaus_spec::load_sdk().expect("definitions");
    let table = jaus_conform::catalogue::markdown(&spec);
    let path = docs();
    let now = std::fs::read_to_string(&path).expect("docs/conformance.md");
    let want = with_table(&now, &table);
    if now == want {
        return;
    }
    if std::env::var_os("UPDATE_DOCS").is_some_and(|v| v == "1") {
        std::fs::write(&path, &want).expect("docs/conformance.md written");
        eprintln!("docs/conformance.md: the table of checks rewritten");
        return;
    }
    let first = now
        .lines()
        .zip(want.lines())
        .position(|(a, b)| a != b)
        .map_or(now.lines().count().min(want.lines().count()), |i| i);
    panic!(
        "docs/conformance.md's table of checks (between {BEGIN} and {END}) differs from \
jaus_conform::catalogue::markdown, from line {}:\n  docs: {}\n  want: {}\n\
Rewrite it with: UPDATE_DOCS=1 cargo test -p jaus-conform --test docs_table",
        first + 1,
        now.lines().nth(first).unwrap_or("(end)"),
        want.lines().nth(first).unwrap_or("(end)"),
    );
}
