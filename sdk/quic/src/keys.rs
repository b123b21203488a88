//! A node's identity on a QUIC data link: a self-signed certificate and its private key
//! (ECDSA P-256), made once by [`generate`] (`jaus keygen NAME`) and kept as two PEM
//! files, `NAME.crt` (given to the far end, which pins it) and `NAME.key` (which stays
//! on the node: mode 0600 on Unix).
//!
//! There is no certificate authority: each end of a link is configured with the far
//! end's certificate and accepts no other ([`crate::pin`]). The certificate's validity
//! dates are not checked; an identity is withdrawn by giving the far end another
//! certificate to pin. [`fingerprint`] names a certificate in logs and documents (the
//! SHA-256 of its DER, as `openssl x509 -noout -fingerprint -sha256` prints it, in
//! lower case and without colons).
//!
//! ```
//! let dir = std::env::temp_dir().join(format!("jaus-quic-keys-doc-{}", std::process::id()));
//! let files = jaus_quic::keys::generate("vehicle", &dir).unwrap();
//! let id = jaus_quic::keys::load_identity(&files.cert, &files.key).unwrap();
//! assert_eq!(jaus_quic::keys::fingerprint(&id.cert), files.fingerprint);
//! // A second `generate` of the same name refuses to overwrite the files.
//! assert!(jaus_quic::keys::generate("vehicle", &dir).is_err());
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```

use std::io::Write;
use std::path::{Path, PathBuf};

use rustls_pki_types::pem::PemObject;
use rustls_pki_types::{CertificateDer, PrivateKeyDer};

/// Why keys could not be made, written or read. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum KeyError {
    /// The name cannot be a file name and a certificate's DNS name.
    #[error("`{0}` is not a key name: use letters, digits, `-`, `_` and `.` (not first)")]
    Name(String),
    /// A file to be written is there already.
    #[error("{}: already exists (not overwritten; remove it or choose another name)", .0.display())]
    Exists(PathBuf),
    /// A file could not be read, created or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the OS said.
        source: std::io::Error,
    },
    /// A file holds no usable PEM section of the kind wanted.
    #[error("{}: not a PEM {what}: {reason}", path.display())]
    Pem {
        /// The file.
        path: PathBuf,
        /// `certificate` or `private key`.
        what: &'static str,
        /// What the PEM reader said.
        reason: String,
    },
    /// The certificate could not be made (rcgen).
    #[error("cannot make the certificate: {0}")]
    Generate(String),
}

/// A node's identity: its certificate (DER) and private key (DER, PKCS#8).
///
/// Its `Debug` shows the certificate's fingerprint only, never the key.
pub struct Identity {
    /// The certificate (self-signed, ECDSA P-256).
    pub cert: CertificateDer<'static>,
    /// The private key.
    pub key: PrivateKeyDer<'static>,
}

impl Identity {
    /// A new identity in memory (not written anywhere): for tests and tools that keep
    /// keys themselves. `name` is the certificate's subject and DNS name.
    pub fn generate(name: &str) -> Result<Self, KeyError> {
        let (cert, key) = make(name)?;
        Ok(Self {
            cert: cert.der().clone(),
            key: PrivateKeyDer::Pkcs8(key.serialize_der().into()),
        })
    }

    /// The certificate's SHA-256 fingerprint ([`fingerprint`]).
    pub fn fingerprint(&self) -> String {
        fingerprint(&self.cert)
    }
}

impl Clone for Identity {
    fn clone(&self) -> Self {
        Self {
            cert: self.cert.clone(),
            key: self.key.clone_key(),
        }
    }
}

impl PartialEq for Identity {
    fn eq(&self, other: &Self) -> bool {
        self.cert == other.cert && self.key.secret_der() == other.key.secret_der()
    }
}

impl Eq for Identity {}

impl std::fmt::Debug for Identity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Identity")
            .field("cert", &format_args!("sha256 {}", self.fingerprint()))
            .field("key", &format_args!("(secret)"))
            .finish()
    }
}

/// The files [`generate`] wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct KeyFiles {
    /// `DIR/NAME.crt`: the certificate, for the far end to pin.
    pub cert: PathBuf,
    /// `DIR/NAME.key`: the private key (mode 0600 on Unix).
    pub key: PathBuf,
    /// The certificate's SHA-256 fingerprint ([`fingerprint`]).
    pub fingerprint: String,
}

/// Makes a new identity named `name` and writes it to `dir` (created if missing) as
/// `NAME.crt` and `NAME.key`; refuses to overwrite either ([`KeyError::Exists`], and
/// then writes neither).
pub fn generate(name: &str, dir: &Path) -> Result<KeyFiles, KeyError> {
    let (cert, key) = make(name)?;
    let files = KeyFiles {
        cert: dir.join(format!("{name}.crt")),
        key: dir.join(format!("{name}.key")),
        fingerprint: fingerprint(cert.der()),
    };
    for p in [&files.cert, &files.key] {
        if p.exists() {
            return Err(KeyError::Exists(p.clone()));
        }
    }
    std::fs::create_dir_all(dir).map_err(|source| KeyError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    // The key first: should the certificate fail, no certificate without its key.
    write_new(&files.key, key.serialize_pem().as_bytes(), true)?;
    if let Err(e) = write_new(&files.cert, cert.pem().as_bytes(), false) {
        let _ = std::fs::remove_file(&files.key);
        return Err(e);
    }
    Ok(files)
}

/// A certificate and key pair named `name`.
fn make(name: &str) -> Result<(rcgen::Certificate, rcgen::KeyPair), KeyError> {
    let ok = |c: char| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.');
    if name.is_empty() || name.len() > 63 || name.starts_with('.') || !name.chars().all(ok) {
        return Err(KeyError::Name(name.to_string()));
    }
    let generate = |e: rcgen::Error| KeyError::Generate(e.to_string());
    let key = rcgen::KeyPair::generate_for(&rcgen::PKCS_ECDSA_P256_SHA256).map_err(generate)?;
    let mut params = rcgen::CertificateParams::new(vec![name.to_string()]).map_err(generate)?;
    params.distinguished_name = rcgen::DistinguishedName::new();
    params
        .distinguished_name
        .push(rcgen::DnType::CommonName, name);
    let cert = params.self_signed(&key).map_err(generate)?;
    Ok((cert, key))
}

/// Writes `bytes` to a new file at `path` (never over an existing one); `secret`: mode
/// 0600 on Unix.
fn write_new(path: &Path, bytes: &[u8], secret: bool) -> Result<(), KeyError> {
    let mut options = std::fs::OpenOptions::new();
    options.write(true).create_new(true);
    #[cfg(unix)]
    if secret {
        use std::os::unix::fs::OpenOptionsExt;
        options.mode(0o600);
    }
    #[cfg(not(unix))]
    let _ = secret;
    let io = |source: std::io::Error| {
        if source.kind() == std::io::ErrorKind::AlreadyExists {
            KeyError::Exists(path.to_path_buf())
        } else {
            KeyError::Io {
                path: path.to_path_buf(),
                source,
            }
        }
    };
    let mut f = options.open(path).map_err(io)?;
    f.write_all(bytes).map_err(io)?;
    f.sync_all().map_err(io)
}

/// Reads a file, the error naming it.
fn read(path: &Path) -> Result<Vec<u8>, KeyError> {
    std::fs::read(path).map_err(|source| KeyError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// The first certificate of the PEM file at `path`.
pub fn load_cert(path: &Path) -> Result<CertificateDer<'static>, KeyError> {
    CertificateDer::from_pem_slice(&read(path)?).map_err(|e| KeyError::Pem {
        path: path.to_path_buf(),
        what: "certificate",
        reason: e.to_string(),
    })
}

/// The first private key (PKCS#8, SEC1 or PKCS#1) of the PEM file at `path`.
pub fn load_key(path: &Path) -> Result<PrivateKeyDer<'static>, KeyError> {
    PrivateKeyDer::from_pem_slice(&read(path)?).map_err(|e| KeyError::Pem {
        path: path.to_path_buf(),
        what: "private key",
        reason: e.to_string(),
    })
}

/// The identity of the PEM files `cert` and `key` (whether the key is the
/// certificate's is checked when a link is set up with it).
pub fn load_identity(cert: &Path, key: &Path) -> Result<Identity, KeyError> {
    Ok(Identity {
        cert: load_cert(cert)?,
        key: load_key(key)?,
    })
}

/// The SHA-256 of a certificate's DER, 64 lower-case hex digits.
///
/// ```
/// let f = jaus_quic::keys::fingerprint(b"abc");
/// assert_eq!(f, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
/// ```
pub fn fingerprint(cert_der: &[u8]) -> String {
    let digest = ring::digest::digest(&ring::digest::SHA256, cert_der);
    digest.as_ref().iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_dir(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("jaus-quic-keys-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn generated_files_load_back_and_are_not_overwritten() {
        let dir = temp_dir("gen");
        let files = generate("station-1", &dir).unwrap();
        assert_eq!(files.cert, dir.join("station-1.crt"));
        assert_eq!(files.key, dir.join("station-1.key"));
        assert_eq!(files.fingerprint.len(), 64);
        let id = load_identity(&files.cert, &files.key).unwrap();
        assert_eq!(id.fingerprint(), files.fingerprint);
        assert!(format!("{id:?}").contains(&files.fingerprint));
        assert!(!format!("{id:?}").contains("PRIVATE"));
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&files.key).unwrap().permissions().mode();
            assert_eq!(mode & 0o777, 0o600);
        }
        let before = std::fs::read(&files.key).unwrap();
        let again = generate("station-1", &dir).unwrap_err();
        assert!(matches!(again, KeyError::Exists(_)), "{again}");
        assert!(again.to_string().contains("station-1.crt"), "{again}");
        assert_eq!(std::fs::read(&files.key).unwrap(), before);
        // Only the key left behind: still refused, and the certificate not written.
        std::fs::remove_file(&files.cert).unwrap();
        assert!(matches!(
            generate("station-1", &dir),
            Err(KeyError::Exists(p)) if p == files.key
        ));
        assert!(!files.cert.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn errors_name_the_file() {
        let dir = temp_dir("errors");
        std::fs::create_dir_all(&dir).unwrap();
        let missing = dir.join("nope.crt");
        let e = load_cert(&missing).unwrap_err();
        assert!(
            e.to_string().starts_with(&missing.display().to_string()),
            "{e}"
        );
        let junk = dir.join("junk.crt");
        std::fs::write(&junk, "not pem").unwrap();
        let e = load_cert(&junk).unwrap_err();
        assert!(
            e.to_string()
                .starts_with(&format!("{}: not a PEM certificate", junk.display())),
            "{e}"
        );
        let e = load_key(&junk).unwrap_err();
        assert!(e.to_string().contains("not a PEM private key"), "{e}");
        for bad in ["", "a b", "../x", ".hidden", "x/y"] {
            assert!(
                matches!(generate(bad, &dir), Err(KeyError::Name(_))),
                "{bad}"
            );
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn identities_differ_and_clone_equal() {
        let a = Identity::generate("a").unwrap();
        let b = Identity::generate("a").unwrap();
        assert_ne!(a.fingerprint(), b.fingerprint());
        assert_eq!(a.clone(), a);
        assert_ne!(a, b);
    }
}
