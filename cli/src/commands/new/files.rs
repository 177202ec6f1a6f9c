//! The files of a new drive crate, as relative paths and contents, before anything is written.

use std::path::PathBuf;

use heck::{ToTitleCase, ToUpperCamelCase};

/// Where the new crate takes `drivebus` and `drivegen` from.
#[derive(Debug, Clone)]
pub enum Dependencies {
    /// The registry (crates.io), by version.
    Registry,
    /// A checkout of the drivegen repository (its `transport/` and `codegen/`), by version and path.
    Checkout(PathBuf),
}

/// What the description folder starts with.
#[derive(Debug, Clone)]
pub enum Description {
    /// The commented skeleton of a Modbus drive, with placeholders to replace.
    Skeleton,
    /// An EDS overlay (`device.toml`) beside a copy of the vendor's EDS.
    EdsOverlay {
        /// File name of the EDS, as the overlay names it.
        eds_name: String,
        /// The EDS's bytes.
        eds: Vec<u8>,
        /// The overlay skeleton `drivegen::eds::import_overlay` wrote.
        overlay: String,
    },
}

/// One file of the crate.
#[derive(Debug, Clone)]
pub struct File {
    /// Path relative to the crate folder.
    pub path: PathBuf,
    /// Contents.
    pub bytes: Vec<u8>,
}

/// The crate `name` with `description`, depending on drivegen's crates through `dependencies`.
pub fn crate_files(name: &str, description: Description, dependencies: &Dependencies) -> Vec<File> {
    let words = Words::of(name);
    let folder = PathBuf::from("descriptions").join(name);
    let mut files = vec![
        text("Cargo.toml", words.fill(&manifest(dependencies))),
        text(
            "build.rs",
            words.fill(include_str!("templates/build.rs.in")),
        ),
        text(
            "src/lib.rs",
            words.fill(include_str!("templates/lib.rs.in")),
        ),
        text(
            "README.md",
            words.fill(include_str!("templates/README.md.in")),
        ),
        text(
            ".gitignore",
            include_str!("templates/gitignore.in").to_string(),
        ),
    ];
    match description {
        Description::Skeleton => files.push(text(
            folder.join("device.toml"),
            words.fill(include_str!("templates/device.toml.in")),
        )),
        Description::EdsOverlay {
            eds_name,
            eds,
            overlay,
        } => {
            files.push(text(folder.join("device.toml"), overlay));
            files.push(File {
                path: folder.join(eds_name),
                bytes: eds,
            });
        }
    }
    files
}

fn text(path: impl Into<PathBuf>, contents: String) -> File {
    File {
        path: path.into(),
        bytes: contents.into_bytes(),
    }
}

/// The Cargo.toml template with its dependency lines filled in.
fn manifest(dependencies: &Dependencies) -> String {
    include_str!("templates/Cargo.toml.in")
        .replace(
            "{drivebus}",
            &dependency(
                "drivebus",
                super::super::DRIVEBUS_VERSION,
                "transport",
                dependencies,
                ", default-features = false",
            ),
        )
        .replace(
            "{drivegen}",
            &dependency(
                "drivegen",
                super::super::DRIVEGEN_VERSION,
                "codegen",
                dependencies,
                "",
            ),
        )
}

fn dependency(
    name: &str,
    version: &str,
    folder: &str,
    dependencies: &Dependencies,
    options: &str,
) -> String {
    match dependencies {
        Dependencies::Registry => format!("{name} = {{ version = \"{version}\"{options} }}"),
        Dependencies::Checkout(root) => {
            let path = root.join(folder).display().to_string().replace('\\', "/");
            format!(
                "# From a drivegen checkout until {name} is on crates.io; then drop `path`.\n\
                 {name} = {{ version = \"{version}\", path = {}{options} }}",
                toml_string(&path)
            )
        }
    }
}

fn toml_string(text: &str) -> String {
    toml::Value::String(text.to_owned()).to_string()
}

/// The names a template uses, derived from the crate name.
struct Words {
    name: String,
    title: String,
    handle: String,
}

impl Words {
    fn of(name: &str) -> Self {
        Self {
            name: name.to_owned(),
            title: name.to_title_case(),
            handle: name.to_upper_camel_case(),
        }
    }

    /// `template` with `{name}`, `{title}` and `{handle}` replaced.
    fn fill(&self, template: &str) -> String {
        template
            .replace("{name}", &self.name)
            .replace("{title}", &self.title)
            .replace("{handle}", &self.handle)
    }
}
