//! What the opt-in tests against the public JSIDL share.

use std::path::Path;

/// Copies the directory `from` to `to`, leaving out the file `skip` (a path relative to
/// `from`, e.g. a set's own copy of the Core basic types).
pub fn copy_without(from: &Path, to: &Path, skip: &Path) {
    std::fs::create_dir_all(to).expect("create the copy's directory");
    for e in std::fs::read_dir(from).expect("read the JSIDL directory") {
        let e = e.expect("read the JSIDL directory");
        let (src, dst) = (e.path(), to.join(e.file_name()));
        if src.ends_with(skip) {
            continue;
        }
        if src.is_dir() {
            copy_without(&src, &dst, skip);
        } else {
            std::fs::copy(&src, &dst).expect("copy a JSIDL file");
        }
    }
}
