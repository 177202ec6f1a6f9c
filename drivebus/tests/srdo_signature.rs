//! SRDO safety signatures against the SWD manual's own numbers: the ten default signatures of
//! 13FFh (lines 3588-3600) computed from the default tables (lines 1736-1934), and the quick
//! start's BABDh (line 4111). See `drivebus::canopen::srdo::signature` for the decisions these
//! vectors settle, and the two printed table values they correct (SRDO9, SRDO16).
#![cfg(feature = "canopen")]

use drivebus::canopen::pdo::MappedObject;
use drivebus::canopen::srdo::{
    signature, verify, SignatureMismatch, SrdoCommunication, SrdoConfig, SrdoDirection, SrdoError,
    VerifyError,
};

/// The quick start's node-ID (line 4100).
const NODE_ID: u32 = 0x10;

fn comm(direction: SrdoDirection, sct_ms: u16, cob_ids: (u32, u32)) -> SrdoCommunication {
    SrdoCommunication {
        direction,
        sct_ms,
        srvt_ms: 20,
        transmission_type: 0xFE,
        cob_id_normal: cob_ids.0,
        cob_id_inverted: cob_ids.1,
    }
}

fn entries(raw: &[u32]) -> Vec<MappedObject> {
    raw.iter().copied().map(MappedObject::from_entry).collect()
}

fn sign(number: u8, communication: SrdoCommunication, mapping: &[u32]) -> u16 {
    let mapping = entries(mapping);
    signature(&SrdoConfig {
        number,
        communication,
        mapping: &mapping,
    })
    .unwrap()
}

/// SRDO1 RX: lines 1736-1746.
fn srdo1(direction: SrdoDirection) -> u16 {
    let ids = (0xFF + 2 * NODE_ID, 0x100 + 2 * NODE_ID);
    sign(1, comm(direction, 50, ids), &[0x6620_0108, 0x6622_0108])
}

#[test]
fn srdo1_default_signature() {
    assert_eq!(srdo1(SrdoDirection::Receive), 0x70AB); // line 3588
}

#[test]
fn quick_start_signature_of_disabled_srdo1() {
    assert_eq!(srdo1(SrdoDirection::Invalid), 0xBABD); // line 4111
}

#[test]
fn srdo2_default_signature() {
    // Lines 1753-1782: SCT 25, COB-IDs 103h/104h, 16 entries.
    let mapping: Vec<u32> = (1..=8u32)
        .flat_map(|i| [0x6621_0008 | (i << 8), 0x6623_0008 | (i << 8)])
        .collect();
    let c = comm(SrdoDirection::Transmit, 25, (0x103, 0x104));
    assert_eq!(sign(2, c, &mapping), 0x8C5F); // line 3589
}

/// SRDO number, SCT, COB-IDs, mapping entries, expected signature.
type Case = (u8, u16, (u32, u32), &'static [u32], u16);

#[test]
fn inactive_srdo_default_signatures() {
    use SrdoDirection::Invalid;
    let cases: [Case; 6] = [
        // SRDO10, lines 1808-1820, signature line 3594.
        (
            10,
            25,
            (0x107, 0x108),
            &[0x6611_0020, 0x661A_0020, 0x6613_0020, 0x661C_0020],
            0x2274,
        ),
        // SRDO11..14, lines 1827-1841, 1848-1858, 1865-1875, 1885-1895; signatures 3595-3598.
        (11, 50, (0x109, 0x10A), &[0x6620_0308, 0x6622_0308], 0x78AE),
        (12, 50, (0x10B, 0x10C), &[0x6620_0408, 0x6622_0408], 0x4052),
        (13, 50, (0x10D, 0x10E), &[0x6620_0508, 0x6622_0508], 0x9968),
        (14, 50, (0x10F, 0x110), &[0x6620_0608, 0x6622_0608], 0x1BF6),
        // SRDO15, lines 1902-1914, signature line 3599.
        (
            15,
            50,
            (0x111, 0x112),
            &[0x6620_0708, 0x6622_0708, 0x6620_0808, 0x6622_0808],
            0x3A94,
        ),
    ];
    for (number, sct, ids, mapping, expected) in cases {
        assert_eq!(
            sign(number, comm(Invalid, sct, ids), mapping),
            expected,
            "SRDO{number}"
        );
    }
}

/// SRDO9 as printed (lines 1789-1801) does not give 6C9Bh (line 3593); with the COB-IDs
/// 105h/106h and the inverted entry 6622 0208h it does.
#[test]
fn srdo9_reproduces_only_with_the_corrected_table() {
    let printed_ids = (0xFF + 2 * NODE_ID, 0x100 + 2 * NODE_ID);
    let printed = sign(
        9,
        comm(SrdoDirection::Invalid, 50, printed_ids),
        &[0x6620_0208, 0x6622_0108],
    );
    assert_ne!(printed, 0x6C9B);
    let corrected = sign(
        9,
        comm(SrdoDirection::Invalid, 50, (0x105, 0x106)),
        &[0x6620_0208, 0x6622_0208],
    );
    assert_eq!(corrected, 0x6C9B);
}

/// SRDO16 as printed (SCT 25 ms, line 1926) does not give 9941h (line 3600); with SCT 50 ms it
/// does.
#[test]
fn srdo16_reproduces_only_with_sct_50() {
    let mapping = [0x2620_0208, 0x2622_0208]; // lines 1933-1934
    let ids = (0x113, 0x114); // lines 1929-1930
    assert_ne!(
        sign(16, comm(SrdoDirection::Invalid, 25, ids), &mapping),
        0x9941
    );
    assert_eq!(
        sign(16, comm(SrdoDirection::Invalid, 50, ids), &mapping),
        0x9941
    );
}

#[test]
fn an_srvt_above_one_byte_is_refused() {
    let mapping = entries(&[0x6620_0108, 0x6622_0108]);
    let mut communication = comm(SrdoDirection::Receive, 500, (0x11F, 0x120));
    communication.srvt_ms = 256;
    let config = SrdoConfig {
        number: 1,
        communication,
        mapping: &mapping,
    };
    assert!(matches!(
        signature(&config),
        Err(SrdoError::BadConfiguration(_))
    ));
}

#[test]
fn a_mismatch_reports_both_values() {
    let mapping = entries(&[0x6620_0108, 0x6622_0108]);
    let config = SrdoConfig {
        number: 1,
        communication: comm(SrdoDirection::Receive, 50, (0x11F, 0x120)),
        mapping: &mapping,
    };
    assert_eq!(verify(&config, 0x70AB), Ok(()));
    assert_eq!(
        verify(&config, 0xBABD),
        Err(VerifyError::Mismatch(SignatureMismatch {
            srdo: 1,
            computed: 0x70AB,
            stored: 0xBABD
        }))
    );
}
