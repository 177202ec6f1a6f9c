//! Reading on one thread and on two gives the same model, parameters and diagnostics: for every
//! file of the EDS corpus and for large generated files full of what the reader warns about.

use std::fmt::Write as _;
use std::path::Path;

use super::{ini_halves, read_bytes_with, typed_parameters, Threads};
use crate::diagnostic::{Diagnostic, FileId, Files};

/// Everything a read gives, rendered exactly (`Debug` shows every field).
fn read(path: &Path, bytes: &[u8], threads: Threads) -> String {
    let mut files = Files::default();
    let mut diagnostics = Vec::new();
    let model = read_bytes_with(path, bytes, &mut files, &mut diagnostics, threads);
    let parameters = typed_parameters(model.entries.clone(), &mut diagnostics);
    let rendered: Vec<String> = diagnostics.iter().map(|d| d.render(&files)).collect();
    format!("{model:#?}\n{parameters:#?}\n{diagnostics:#?}\n{rendered:#?}")
}

fn assert_same(path: &Path, bytes: &[u8]) {
    let one = read(path, bytes, Threads::One);
    let two = read(path, bytes, Threads::Two);
    // Not `assert_eq!`: a difference in megabytes of text is better found by its first line.
    if let Some((n, (a, b))) = one
        .lines()
        .zip(two.lines())
        .enumerate()
        .find(|(_, (a, b))| a != b)
    {
        panic!("{}: line {n} differs:\none: {a}\ntwo: {b}", path.display());
    }
    assert_eq!(one.len(), two.len(), "{}", path.display());
    assert_eq!(read(path, bytes, Threads::Auto), one, "{}", path.display());
}

#[test]
fn every_corpus_file_reads_the_same_on_two_threads() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/eds");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if super::is_eds_path(&path) {
            assert_same(&path, &std::fs::read(&path).unwrap());
            count += 1;
        }
    }
    assert!(count >= 25, "the corpus holds {count} files");
}

/// An EDS of `objects` objects with, every few objects, something the reader warns about or must
/// get right across the two halves: unknown keys and sections, repeated keys and sections, bad
/// values, missing names, orphan and misplaced sub-sections, compact arrays, names clashing
/// across the file, objects out of order, stray lines and comments.
fn awkward_eds(objects: u16) -> String {
    let mut eds = String::from("; generated\n[FileInfo]\nFileName=awkward.eds\n\n");
    eds.push_str("[DeviceComissioning]\nNodeID=5\nColour=blue\n\n");
    for i in 0..objects {
        // Out of order every 97 objects: the dictionary sorts them.
        let index = 0x2000 + if i % 97 == 13 { objects + i } else { i };
        match i % 7 {
            0 | 3 => {
                let _ = write!(
                    eds,
                    "[{index:04X}]\nParameterName=Speed {}\nDataType=0x0007\nAccessType=rw\nLowLimit=0\nHighLimit=$NODEID+4\nDefaultValue={}\nPDOMapping=1\n",
                    i % 5,
                    i
                );
            }
            1 => {
                let _ = write!(eds, "[{index:04X}]\nParameterName=Record\nObjectType=0x9\nSubNumber=3\n\n[{index:04X}sub0]\nParameterName=Highest sub-index supported\nDataType=0x0005\nAccessType=ro\nDefaultValue=2\n\n[{index:04X}sub1]\nParameterName=COB-ID\nDataType=0x0007\nAccessType=rw\nDefaultValue=$NODEID+0x180\n\n[{index:04x}SUB2]\nParameterName=Count\nDataType=0x0005\nAccessType=ro\nwhatever=1\n");
            }
            2 => {
                let _ = write!(eds, "[{index:04X}]\nDataType=0x0004\nAccessType=bogus\nDefaultValue=zz\nDataType=0x0005\n garbage line\n[{index:04X}sub3]\nParameterName=Stray\n");
            }
            4 => {
                let _ = write!(eds, "[{index:04X}sub1]\nParameterName=Early\nDataType=0x0005\nAccessType=ro\n\n[{index:04X}]\nParameterName=Array\nObjectType=0x8\nSubNumber=2\n; comment\n[{index:04X}sub0]\nParameterName=Number\nDataType=0x0005\nAccessType=ro\nPDOMapping=7\n");
            }
            5 => {
                let _ = write!(eds, "[{index:04X}]\nParameterName=Compact\nObjectType=0x8\nCompactSubObj=3\nDataType=0x0006\nAccessType=rw\n\n[{index:04X}Name]\nNbOfEntries=1\n2=Second\n\n[{index:04X}Value]\nNbOfEntries=1\n1=0x10\n");
            }
            _ => {
                let _ = write!(eds, "[{index:04X}]\nParameterName=Count\nObjectType=0x7\nDataType=0x00FF\nAccessType=const\nDefaultValue=1 ; trailing\n[{index:04X}]\nDescription=reopened\nDefaultValue=2\n[Mystery{i}]\nx=1\n");
            }
        }
        eds.push('\n');
    }
    eds.push_str("[DeviceCommissioning]\nNodeID=300\n\n[DeviceInfo]\nVendorName=Awkward\nProductName=Awkward\n\n[Comments]\nLines=1\nLine1=end\n");
    eds
}

#[test]
fn large_awkward_files_read_the_same_on_two_threads() {
    for objects in [1, 2, 7, 50, 400, 2000] {
        let eds = awkward_eds(objects);
        assert_same(Path::new("awkward.eds"), eds.as_bytes());
    }
}

#[test]
fn a_section_repeated_across_the_halves_reads_the_same() {
    let mut eds = awkward_eds(400);
    eds.push_str("\n[FileInfo]\nFileName=again.eds\n[2000]\nParameterName=Again\n");
    assert_same(Path::new("repeated.eds"), eds.as_bytes());
    let mut diagnostics = Vec::new();
    let halves = ini_halves::parse(FileId(0), &eds, &mut diagnostics);
    assert!(halves.is_none(), "one pass reports the repeated sections");
    assert!(diagnostics.is_empty());
}

#[test]
fn large_files_are_read_in_halves() {
    let eds = awkward_eds(400);
    let mut diagnostics: Vec<Diagnostic> = Vec::new();
    assert!(ini_halves::parse(FileId(0), &eds, &mut diagnostics).is_some());
    assert!(!diagnostics.is_empty());
}
