//! `jaus-gen`: validate JAUS definitions and generate Rust (and docs) from them.

use clap::{Args, Parser, Subcommand, ValueEnum};
use jaus_gen::diff::Severity;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "jaus-gen",
    version,
    about = "Generate the typed JAUS SDK from YAML definitions"
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
}

/// Which definitions to load.
#[derive(Args)]
struct SpecArgs {
    /// Directories of `*.yaml` definitions (default: the RA 3.3 set of jaus-spec).
    #[arg(long = "spec", value_name = "DIR")]
    spec: Vec<PathBuf>,
    /// Extra definition files loaded after the directories.
    #[arg(long = "overlay", value_name = "FILE")]
    overlays: Vec<PathBuf>,
}

#[derive(Subcommand)]
enum Cmd {
    /// Validate definitions and write the generated Rust (`messages.rs`) to a directory.
    Generate {
        #[command(flatten)]
        defs: SpecArgs,
        /// Output directory.
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
        /// Directory of templates overriding the built-in ones.
        #[arg(long, value_name = "DIR")]
        templates: Option<PathBuf>,
        /// Gate each non-core group behind a cargo feature of the same name.
        #[arg(long)]
        feature_gates: bool,
    },
    /// Render the reference documentation: one Markdown page per group and an index.
    Docs {
        #[command(flatten)]
        defs: SpecArgs,
        /// Output directory.
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Write a Wireshark/tshark dissector (Lua) for every message of the definitions,
    /// a vendor's overlays included: JUDP and "JAUS01.0" framing, the header, every
    /// body field, multi-packet messages reassembled.
    Wireshark {
        #[command(flatten)]
        defs: SpecArgs,
        /// Directories of AS-4 definitions (`extends: none`, e.g. sdk/as4/defs, then a
        /// vendor's AS-4 messages): the dissector then also reads AS5669A (JUDP version
        /// 2) and every AS-4 message of them.
        #[arg(long = "as4-spec", value_name = "DIR")]
        as4_spec: Vec<PathBuf>,
        /// Output file.
        #[arg(long, value_name = "FILE", default_value = "jaus.lua")]
        out: PathBuf,
    },
    /// Validate definitions only; print every problem as file:line:column and exit 1.
    Check {
        #[command(flatten)]
        defs: SpecArgs,
    },
    /// List every change between two revisions of the definitions, each classified
    /// compatible, source-breaking or wire-breaking. Exit status: 0 when nothing is at
    /// least as severe as --fail-on, 1 when something is, 2 on a usage or load error.
    Diff {
        /// The old revision: a directory of YAML, a YAML file, a comma-separated list of
        /// both (`jaus-spec/defs,acme.yaml`), a git revision `REV:PATH`
        /// (`HEAD~1:jaus-spec/defs`), a lock file, or a directory of JSIDL (`*.xml`
        /// files and no YAML; several, comma-separated, are imported together). YAML without the SDK's `core` group
        /// and without `extends: none` is a vendor's overlay: it is read on the SDK's
        /// built-in definitions and only its own items are compared.
        old: String,
        /// The new revision, written the same way.
        new: String,
        /// Output format.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        /// The least severe change that makes the exit status 1.
        #[arg(long, value_enum, default_value_t = FailOn::WireBreaking)]
        fail_on: FailOn,
        /// Read every directory named as JSIDL (imported as `jaus-gen jsidl` does), even
        /// one that also holds YAML.
        #[arg(long)]
        jsidl: bool,
    },
    /// Write (pin) the lock file of a definition set (the wire-layout snapshot that
    /// `Builder::lock` checks); with --check, compare instead and exit 1 on any change.
    /// A vendor's overlay alone (`--overlay defs/my.yaml`) is read on the SDK's
    /// definitions and locked with its own items only, as its build checks it.
    Lock {
        #[command(flatten)]
        defs: SpecArgs,
        /// The lock file.
        path: PathBuf,
        /// Compare the definitions with the lock file instead of writing it.
        #[arg(long)]
        check: bool,
    },
    /// Import JSIDL (AS5684) service definitions and declared type sets: write them as
    /// YAML definitions (one file per JSIDL file; each DIR, read recursively, is one
    /// group) and validate the result. Anything the definition language cannot
    /// represent is an error with the JSIDL file, line and element.
    Jsidl {
        /// Directories of JSIDL `*.xml` files; references resolve across all of them.
        #[arg(required = true, value_name = "DIR")]
        dirs: Vec<PathBuf>,
        /// Output directory for the YAML.
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Write a new vendor crate: its own experimental messages and a component (YAML
    /// extending the SDK's definitions), build.rs, a node on UDP, a test on the bus.
    New {
        /// Crate name, also its directory (under --dir).
        name: String,
        /// Directory to create the crate in (default: the current directory).
        #[arg(long, value_name = "DIR", default_value = ".")]
        dir: PathBuf,
        /// Take the SDK from a checkout of its workspace (relative to the new crate, or
        /// absolute) instead of its published version.
        #[arg(long, value_name = "DIR")]
        sdk_path: Option<PathBuf>,
        /// Leave out the `[workspace]` table (the crate will be a member of an
        /// enclosing workspace).
        #[arg(long)]
        member: bool,
        /// An AS-4 crate: a service of its own on jaus-as4's definitions (inheriting
        /// Access Control), its guards and actions, a node on UDP, a test in which an
        /// AS-4 client drives it.
        #[arg(long)]
        as4: bool,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum Format {
    Text,
    Json,
}

#[derive(Clone, Copy, ValueEnum)]
enum FailOn {
    Compatible,
    SourceBreaking,
    WireBreaking,
}

impl From<FailOn> for Severity {
    fn from(f: FailOn) -> Severity {
        match f {
            FailOn::Compatible => Severity::Compatible,
            FailOn::SourceBreaking => Severity::SourceBreaking,
            FailOn::WireBreaking => Severity::WireBreaking,
        }
    }
}

/// `jaus-gen diff`: 0, 1, or 2 on an error.
fn diff(old: &str, new: &str, format: Format, fail_on: Severity, jsidl: bool) -> ExitCode {
    let load = |arg: &str| jaus_gen::revision::load_with(arg, jsidl);
    let (old, new) = match (load(old), load(new)) {
        (Ok(o), Ok(n)) => (o, n),
        (o, n) => {
            for e in [o.err(), n.err()].into_iter().flatten() {
                eprintln!("{e}");
            }
            return ExitCode::from(2);
        }
    };
    let d = jaus_gen::diff::diff(&old, &new);
    match format {
        Format::Text => print!("{}", d.to_text()),
        Format::Json => print!("{}", d.to_json()),
    }
    ExitCode::from(d.exit_status(fail_on))
}

/// `jaus-gen lock`: the definitions are read as `jaus-gen diff` reads a revision, so an
/// overlay alone (`--overlay defs/my.yaml`, or `--spec defs` holding only it) is locked
/// on the SDK's definitions with its own items only, as its build locks it.
fn lock(defs: SpecArgs, path: PathBuf, check: bool) -> Result<(), jaus_gen::Error> {
    let paths: Vec<PathBuf> = if defs.spec.is_empty() && defs.overlays.is_empty() {
        vec![jaus_spec::defs_dir()]
    } else {
        defs.spec.into_iter().chain(defs.overlays).collect()
    };
    let snap = jaus_gen::revision::load_paths(&paths)?;
    if !check {
        jaus_gen::write_if_changed(&path, &jaus_gen::lock::to_text(&snap))?;
        println!("wrote {}", path.display());
        return Ok(());
    }
    let text = std::fs::read_to_string(&path).map_err(|source| jaus_gen::Error::Io {
        path: path.clone(),
        source,
    })?;
    let old = jaus_gen::lock::parse(&text, &path.display().to_string())
        .map_err(jaus_gen::Error::Revision)?;
    let d = jaus_gen::diff::diff(&old, &snap);
    print!("{}", d.to_text());
    if d.changes.is_empty() {
        Ok(())
    } else {
        Err(jaus_gen::Error::Lock(format!(
            "{}: differs from the definitions; rewrite it with the same arguments \
             without --check",
            path.display()
        )))
    }
}

/// `jaus-gen jsidl`: import, validate, write, and say what each file gave.
fn jsidl(dirs: &[PathBuf], out: &std::path::Path) -> Result<(), jaus_gen::Error> {
    let import = jaus_jsidl::import(dirs)?;
    // Written first, so that a validation error points into a file that exists.
    let files = import.write(out)?;
    let spec = jaus_spec::load_texts(import.texts(out))?;
    for (f, p) in import.files.iter().zip(&files) {
        println!(
            "wrote {} ({} services, {} messages, {} types)",
            p.display(),
            f.services,
            f.messages,
            f.types
        );
    }
    println!(
        "ok: {} services, {} messages, {} types in {} file(s)",
        spec.services.len(),
        spec.messages.len(),
        spec.types.len(),
        files.len()
    );
    Ok(())
}

fn builder(defs: SpecArgs) -> jaus_gen::Builder {
    let dirs = if defs.spec.is_empty() && defs.overlays.is_empty() {
        vec![jaus_spec::defs_dir()]
    } else {
        defs.spec
    };
    let mut b = jaus_gen::Builder::new().emit_rerun_if_changed(false);
    for d in dirs {
        b = b.spec_dir(d);
    }
    for o in defs.overlays {
        b = b.overlay(o);
    }
    b
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.cmd {
        Cmd::Diff {
            old,
            new,
            format,
            fail_on,
            jsidl,
        } => return diff(&old, &new, format, fail_on.into(), jsidl),
        Cmd::Lock { defs, path, check } => lock(defs, path, check),
        Cmd::Jsidl { dirs, out } => jsidl(&dirs, &out),
        Cmd::New {
            name,
            dir,
            sdk_path,
            member,
            as4,
        } => {
            let mut c = jaus_gen::scaffold::NewCrate::new(&name);
            if let Some(p) = sdk_path {
                c.sdk = jaus_gen::scaffold::Sdk::Path(p);
            }
            c.standalone = !member;
            c.as4 = as4;
            let root = dir.join(&name);
            c.write(&root).map(|files| {
                for f in files {
                    println!("wrote {}", f.display());
                }
                let run = if as4 {
                    "cargo run -- --bind 127.0.0.1:3794 --id 30.1.5"
                } else {
                    "cargo run -- --seconds 10"
                };
                println!("next: cd {} && cargo test && {run}", root.display());
            })
        }
        Cmd::Generate {
            defs,
            out,
            templates,
            feature_gates,
        } => {
            let mut b = builder(defs).out_dir(&out).feature_gates(feature_gates);
            if let Some(t) = templates {
                b = b.templates_dir(t);
            }
            b.generate().map(|g| {
                for f in &g.files {
                    println!(
                        "wrote {} ({} messages, {} types)",
                        f.display(),
                        g.messages,
                        g.types
                    );
                }
            })
        }
        Cmd::Docs { defs, out } => builder(defs).load().and_then(|s| {
            let files = jaus_gen::render_docs(&s, &out)?;
            println!("wrote {} page(s) to {}", files.len(), out.display());
            Ok(())
        }),
        Cmd::Wireshark {
            defs,
            as4_spec,
            out,
        } => builder(defs).load().and_then(|s| {
            let as4 = if as4_spec.is_empty() {
                None
            } else {
                Some(jaus_spec::load_dirs(&as4_spec)?)
            };
            let lua = jaus_gen::wireshark::dissector_for(&s, as4.as_ref());
            std::fs::write(&out, lua).map_err(|source| jaus_gen::Error::Io {
                path: out.clone(),
                source,
            })?;
            println!(
                "wrote {} ({} messages, {} types)",
                out.display(),
                s.messages.len(),
                s.types.len()
            );
            Ok(())
        }),
        Cmd::Check { defs } => builder(defs).load().map(|s| {
            println!(
                "ok: {} messages, {} types, {} components in {} file(s)",
                s.messages.len(),
                s.types.len(),
                s.components.len(),
                s.sources.len()
            );
        }),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}
