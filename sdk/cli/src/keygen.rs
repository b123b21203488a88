//! `jaus keygen NAME [--dir DIR]`: a node's identity for authenticated QUIC data links
//! (`jaus_quic::keys`): `DIR/NAME.crt`, the self-signed certificate the far end pins
//! (its node file's `peer_cert`), and `DIR/NAME.key`, the private key, which stays on
//! this node (mode 0600 on Unix).

use std::io::Write;
use std::path::Path;

/// Writes `NAME.crt` and `NAME.key` to `dir` (created if missing), never over existing
/// files, and prints both paths and the certificate's SHA-256 fingerprint.
pub fn keygen(name: &str, dir: &Path, out: &mut impl Write) -> Result<(), String> {
    let files = jaus_quic::keys::generate(name, dir).map_err(|e| e.to_string())?;
    let _ = writeln!(
        out,
        "certificate: {}  (give it to the far end: its link's `peer_cert`)",
        files.cert.display()
    );
    let _ = writeln!(
        out,
        "private key: {}  (keep it on this node: its link's `key`)",
        files.key.display()
    );
    let _ = writeln!(out, "fingerprint (SHA-256): {}", files.fingerprint);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_both_files_prints_them_and_refuses_to_overwrite() {
        let dir = std::env::temp_dir().join(format!("jaus-keygen-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut out = Vec::new();
        keygen("vehicle", &dir, &mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        let (crt, key) = (dir.join("vehicle.crt"), dir.join("vehicle.key"));
        assert!(text.contains(&crt.display().to_string()), "{text}");
        assert!(text.contains(&key.display().to_string()), "{text}");
        let id = jaus_quic::keys::load_identity(&crt, &key).unwrap();
        assert!(text.contains(&format!("fingerprint (SHA-256): {}", id.fingerprint())));
        let again = keygen("vehicle", &dir, &mut Vec::new()).unwrap_err();
        assert!(again.contains("already exists"), "{again}");
        assert_eq!(
            jaus_quic::keys::load_identity(&crt, &key).unwrap(),
            id,
            "untouched"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
