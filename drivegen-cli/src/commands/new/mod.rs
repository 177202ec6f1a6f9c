//! `drivegen new`: a drive crate that builds at once — Cargo.toml, build.rs, src/lib.rs, a README
//! and a description (a commented skeleton, or an overlay of the vendor's EDS).

mod files;
mod name;
mod staging;

use std::path::{Path, PathBuf};

use files::{Dependencies, Description};

use crate::error::CliError;

/// Arguments of `new`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Folder to create (missing or empty); its last component is the crate name.
    path: PathBuf,
    /// Crate name, if not the folder's name.
    #[arg(long)]
    name: Option<String>,
    /// Start from the vendor's EDS: copy it and write an overlay skeleton for it.
    #[arg(long, value_name = "EDS")]
    from: Option<PathBuf>,
    /// Take drivebus and drivegen from this drivegen checkout (default: the checkout this
    /// `drivegen` was installed from, if any; otherwise crates.io).
    #[arg(long, value_name = "DIR")]
    drivegen_path: Option<PathBuf>,
}

/// Checks the name and the inputs, then writes the whole crate or nothing.
pub fn run(args: Args) -> Result<(), CliError> {
    let name = crate_name(&args)?;
    let description = match &args.from {
        Some(eds) => eds_overlay(eds)?,
        None => Description::Skeleton,
    };
    let dependencies = dependencies(args.drivegen_path.as_deref())?;
    let files = files::crate_files(&name, description, &dependencies);
    staging::create_folder(&args.path, &files).map_err(|e| CliError::Usage(e.to_string()))?;
    println!("created drive crate `{name}` in {}", args.path.display());
    if let Dependencies::Checkout(root) = &dependencies {
        println!(
            "drivebus and drivegen come from the checkout {}",
            root.display()
        );
    }
    println!(
        "next: edit {}/descriptions/{name}/device.toml, then `cargo build` there",
        args.path.display()
    );
    Ok(())
}

fn crate_name(args: &Args) -> Result<String, CliError> {
    let name = match (&args.name, args.path.file_name()) {
        (Some(name), _) => name.clone(),
        (None, Some(folder)) => folder.to_string_lossy().into_owned(),
        (None, None) => {
            return Err(CliError::Usage(format!(
                "{} names no folder to take the crate name from: give --name",
                args.path.display()
            )))
        }
    };
    name::check(&name)
        .map_err(|why| CliError::Usage(format!("`{name}` cannot be a crate name: {why}")))?;
    Ok(name)
}

/// The EDS and its overlay skeleton, which lie side by side in the new crate as `device.toml`
/// and the EDS's own file name; an EDS whose skeleton does not check makes no crate.
fn eds_overlay(eds: &Path) -> Result<Description, CliError> {
    let beside = eds.with_file_name("device.toml");
    let imported = drivegen::eds::import_overlay(eds, &beside)
        .map_err(|e| CliError::Invalid(e.to_string()))?;
    if !imported.checks() {
        return Err(CliError::Invalid(format!(
            "{}
the overlay imported from {} does not check: no crate was made",
            imported.checked.render(),
            eds.display()
        )));
    }
    let overlay = imported.overlay;
    let bytes = std::fs::read(eds)
        .map_err(|e| CliError::Io(format!("cannot read {}: {e}", eds.display())))?;
    let eds_name = eds
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| CliError::Usage(format!("{} names no file", eds.display())))?;
    Ok(Description::EdsOverlay {
        eds_name,
        eds: bytes,
        overlay,
    })
}

/// The checkout given, else the one this binary was built from, else the registry.
fn dependencies(given: Option<&Path>) -> Result<Dependencies, CliError> {
    match given {
        Some(dir) => {
            let root = dir
                .canonicalize()
                .map_err(|e| CliError::Usage(format!("--drivegen-path {}: {e}", dir.display())))?;
            if is_checkout(&root) {
                Ok(Dependencies::Checkout(root))
            } else {
                Err(CliError::Usage(format!(
                    "{} is no drivegen checkout (no drivebus-model/, drivebus/ and codegen/ crates)",
                    root.display()
                )))
            }
        }
        None => Ok(built_from_checkout().map_or(Dependencies::Registry, Dependencies::Checkout)),
    }
}

/// The drivegen checkout this binary was compiled in (`cargo install --path drivegen-cli`), if it is
/// still there; a binary built from the published crate has none.
fn built_from_checkout() -> Option<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()?
        .canonicalize()
        .ok()?;
    is_checkout(&root).then_some(root)
}

fn is_checkout(root: &Path) -> bool {
    // drivebus and drivegen take drivebus-model from the checkout too.
    [
        "drivebus-model/Cargo.toml",
        "drivebus/Cargo.toml",
        "codegen/Cargo.toml",
    ]
    .iter()
    .all(|manifest| root.join(manifest).is_file())
}
