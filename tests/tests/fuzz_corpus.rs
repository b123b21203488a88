//! Replays the committed fuzz corpora (`fuzz/corpus/<target>/`, minimised by
//! `cargo fuzz cmin`) and every recorded crash (`fuzz/regressions/<target>/`) through
//! the harnesses the fuzzers run (`jaus_tests::fuzz`), on stable, in the normal suite.

use std::path::Path;

fn replay(target: &str, run: fn(&[u8])) -> usize {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz");
    let mut n = 0;
    for dir in ["corpus", "regressions"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir).join(target)) else {
            continue;
        };
        let mut files: Vec<_> = entries.filter_map(Result::ok).map(|e| e.path()).collect();
        files.sort();
        for f in files {
            let data = std::fs::read(&f).unwrap();
            let r = std::panic::catch_unwind(|| run(&data));
            assert!(r.is_ok(), "{target}: {} fails", f.display());
            n += 1;
        }
    }
    n
}

#[test]
fn packet_corpus() {
    assert!(replay("packet", jaus_tests::fuzz::packet) > 100);
}

#[test]
fn json_corpus() {
    assert!(replay("json", jaus_tests::fuzz::json) > 100);
}

#[test]
fn node_corpus() {
    assert!(replay("node", jaus_tests::fuzz::node) > 100);
}

#[test]
fn spec_yaml_corpus() {
    assert!(replay("spec_yaml", jaus_tests::fuzz::spec_yaml) > 10);
}

#[test]
fn runtime_corpus() {
    assert!(replay("runtime", jaus_tests::fuzz::runtime) >= 5);
}

#[test]
fn as4_corpus() {
    assert!(replay("as4", jaus_tests::fuzz::as4) >= 4);
}

#[test]
fn jtcp_corpus() {
    assert!(replay("jtcp", jaus_tests::fuzz::jtcp) >= 4);
}

#[test]
fn jserial_corpus() {
    assert!(replay("jserial", jaus_tests::fuzz::jserial) >= 4);
}
