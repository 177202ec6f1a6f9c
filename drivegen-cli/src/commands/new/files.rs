//! The files of a new drive crate, as relative paths and contents, before anything is written.

use std::path::PathBuf;

use heck::{ToTitleCase, ToUpperCamelCase};

/// Where the new crate takes `drivebus` and `drivegen` from.
#[derive(Debug, Clone)]
pub enum Dependencies {
    /// The registry (crates.io), by version.
    Registry,
    /// A checkout of the drivegen repository (its `drivebus/` and `codegen/`, which take
    /// `drivebus-model/` beside them), by version and path.
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
                "drivebus",
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

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    fn manifest_of(dependencies: &Dependencies) -> toml::Table {
        let files = crate_files("acme-fd3", Description::Skeleton, dependencies);
        let manifest = files
            .iter()
            .find(|f| f.path == Path::new("Cargo.toml"))
            .unwrap();
        std::str::from_utf8(&manifest.bytes)
            .unwrap()
            .parse()
            .unwrap()
    }

    fn dependency<'a>(manifest: &'a toml::Table, table: &str, name: &str) -> &'a toml::Table {
        manifest[table][name].as_table().unwrap()
    }

    #[test]
    fn from_the_registry_the_dependencies_have_versions_only() {
        let manifest = manifest_of(&Dependencies::Registry);
        let drivebus = dependency(&manifest, "dependencies", "drivebus");
        assert_eq!(drivebus["version"].as_str(), Some("0.1"));
        assert_eq!(drivebus["default-features"].as_bool(), Some(false));
        assert!(!drivebus.contains_key("path"));
        let drivegen = dependency(&manifest, "build-dependencies", "drivegen");
        assert_eq!(drivegen["version"].as_str(), Some("0.1"));
        assert!(!drivegen.contains_key("path"));
    }

    #[test]
    fn from_a_checkout_the_dependencies_also_have_paths() {
        let root = PathBuf::from("/src/drive \"gen\"");
        let manifest = manifest_of(&Dependencies::Checkout(root.clone()));
        let drivebus = dependency(&manifest, "dependencies", "drivebus");
        assert_eq!(drivebus["version"].as_str(), Some("0.1"));
        let expected = root.join("drivebus").display().to_string();
        assert_eq!(drivebus["path"].as_str(), Some(expected.as_str()));
        let drivegen = dependency(&manifest, "build-dependencies", "drivegen");
        let expected = root.join("codegen").display().to_string();
        assert_eq!(drivegen["path"].as_str(), Some(expected.as_str()));
    }

    #[test]
    fn the_names_follow_the_crate_name() {
        let files = crate_files("acme-fd3", Description::Skeleton, &Dependencies::Registry);
        let text = |path: &str| {
            let file = files.iter().find(|f| f.path == Path::new(path)).unwrap();
            String::from_utf8(file.bytes.clone()).unwrap()
        };
        let description = text("descriptions/acme-fd3/device.toml");
        assert!(description.contains("name = \"Acme Fd3\""), "{description}");
        assert!(
            description.contains("handle = \"AcmeFd3\""),
            "{description}"
        );
        assert!(text("build.rs").contains("Builder::new(\"descriptions/acme-fd3\")"));
        assert!(!files
            .iter()
            .any(|f| String::from_utf8_lossy(&f.bytes).contains("{name}")));
    }
}
