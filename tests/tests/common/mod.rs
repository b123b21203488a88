//! Shared by the tests that run the `jaus` binary as a process or need a free port.
//!
//! The binary belongs to the `jaus-cli` package, so `CARGO_BIN_EXE_jaus` is not available
//! here. It is found next to the test's executable (`<target>/<profile>/jaus`, the test
//! runs from `<target>/<profile>/deps/`) after one `cargo build -p jaus-cli --bin jaus`,
//! which is a quick no-op when the binary is up to date and keeps it from going stale.
//! `JAUS_BIN` overrides the path (and skips the build).

// An AS-4 client of a node's gateway on SimNet; killed and restarted `jaus node`
// processes; an operator station in the test.
#[allow(dead_code)]
pub mod as4;
#[allow(dead_code)]
pub mod process;
#[allow(dead_code)]
pub mod station;

use std::net::UdpSocket;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// Path of the `jaus` binary, built once per test process.
#[allow(dead_code)]
pub fn jaus_bin() -> &'static Path {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| {
        if let Some(p) = std::env::var_os("JAUS_BIN") {
            return PathBuf::from(p);
        }
        let exe = std::env::current_exe().expect("test executable path");
        let deps = exe.parent().expect("deps directory");
        let profile_dir = if deps.file_name().is_some_and(|n| n == "deps") {
            deps.parent().expect("profile directory")
        } else {
            deps
        };
        let bin = profile_dir.join(format!("jaus{}", std::env::consts::EXE_SUFFIX));
        let target_dir = profile_dir.parent().expect("target directory");
        let mut cmd = Command::new(env!("CARGO"));
        cmd.args(["build", "--quiet", "-p", "jaus-cli", "--bin", "jaus"])
            .arg("--manifest-path")
            .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("../Cargo.toml"))
            .arg("--target-dir")
            .arg(target_dir);
        match profile_dir.file_name().and_then(|n| n.to_str()) {
            Some("debug") | None => {}
            Some("release") => {
                cmd.arg("--release");
            }
            Some(other) => {
                cmd.args(["--profile", other]);
            }
        }
        let status = cmd.status().expect("run cargo build");
        assert!(
            status.success(),
            "cargo build -p jaus-cli --bin jaus failed"
        );
        assert!(bin.is_file(), "jaus binary not found at {}", bin.display());
        bin
    })
}

/// A free UDP port on 127.0.0.1 (bound then released; good enough for a test).
#[allow(dead_code)]
pub fn free_port() -> u16 {
    UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

/// A log writer that keeps what is logged, for tests that assert on a log: `capture`
/// installs it (warnings and errors) as the current thread's subscriber until the guard
/// is dropped.
#[allow(dead_code)]
#[derive(Clone, Default)]
pub struct LogBuffer(pub std::sync::Arc<std::sync::Mutex<Vec<u8>>>);

#[allow(dead_code)]
impl LogBuffer {
    /// Logs warnings and errors of this thread here until the guard is dropped.
    #[must_use = "logging is captured until the guard is dropped"]
    pub fn capture(&self) -> impl Sized {
        let buf = self.clone();
        let subscriber = tracing_subscriber::fmt()
            .with_writer(move || buf.clone())
            .with_ansi(false)
            .with_max_level(tracing_subscriber::filter::LevelFilter::WARN)
            .finish();
        tracing_subscriber::util::SubscriberInitExt::set_default(subscriber)
    }

    /// What was logged so far.
    pub fn text(&self) -> String {
        String::from_utf8_lossy(&self.0.lock().unwrap()).into_owned()
    }
}

impl std::io::Write for LogBuffer {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(b);
        Ok(b.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}
