//! `jaus-gen`: validate JAUS definitions and generate Rust (and docs) from them.

use clap::{Args, Parser, Subcommand};
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
    /// Validate definitions only; print every problem as file:line:column and exit 1.
    Check {
        #[command(flatten)]
        defs: SpecArgs,
    },
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
