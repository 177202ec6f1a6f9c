//! The bits of the controlword and statusword whose meaning depends on the mode of operation,
//! and the CiA 402 numbers of the modes that give them one (CiA 402-2; the Kinco manual's
//! controlwords 0x2F→0x3F, 0x4F→0x5F, 0x0F→0x1F and statuswords 0xD437 / 0xC037,
//! `003_8cc8f7f4f05b8633.txt` lines 1935-1936, 2498, 2513). One definition for the procedures of
//! the master and the simulated drive.

/// Mode of operation 1: profile position (pp).
pub const PROFILE_POSITION: i8 = 1;
/// Mode of operation 3: profile velocity (pv).
pub const PROFILE_VELOCITY: i8 = 3;
/// Mode of operation 4: profile torque (tq).
pub const PROFILE_TORQUE: i8 = 4;
/// Mode of operation 6: homing (hm).
pub const HOMING: i8 = 6;
/// Mode of operation 8: cyclic synchronous position (csp).
pub const CYCLIC_SYNC_POSITION: i8 = 8;
/// Mode of operation 9: cyclic synchronous velocity (csv).
pub const CYCLIC_SYNC_VELOCITY: i8 = 9;
/// Mode of operation 10: cyclic synchronous torque (cst).
pub const CYCLIC_SYNC_TORQUE: i8 = 10;

/// Controlword bit 4 — pp: new set-point (taken on the rising edge); hm: homing operation start.
pub const NEW_SET_POINT: u16 = 1 << 4;
/// Controlword bit 5 — pp: change set immediately (a new set-point replaces the one in progress
/// instead of following it).
pub const CHANGE_IMMEDIATELY: u16 = 1 << 5;
/// Controlword bit 6 — pp: the target position is relative (to the preceding target).
pub const RELATIVE: u16 = 1 << 6;

/// Statusword bit 10: target reached (pp: on the target within the position window; hm: homing
/// ended or halted; pv: at the target velocity within the velocity window; tq: at the target
/// torque).
pub const TARGET_REACHED: u16 = 1 << 10;
/// Statusword bit 12 — pp: set-point acknowledge; hm: homing attained.
pub const SET_POINT_ACKNOWLEDGE: u16 = 1 << 12;
/// Statusword bit 12 in homing mode: homing attained.
pub const HOMING_ATTAINED: u16 = 1 << 12;
/// Statusword bit 12 in profile velocity mode: the speed is zero (within the velocity threshold
/// 606Fh).
pub const SPEED_ZERO: u16 = 1 << 12;
/// Statusword bit 13 in profile velocity mode: maximum slippage error.
pub const MAX_SLIPPAGE: u16 = 1 << 13;
/// Statusword bit 12 in the cyclic synchronous modes: the drive follows the command value (the
/// set points the master sends each SYNC); clear, it ignores them (CiA 402-2, csp/csv/cst).
pub const FOLLOWS_COMMAND: u16 = 1 << 12;
/// Statusword bit 13 — pp and csp: following error; hm: homing error.
pub const FOLLOWING_ERROR: u16 = 1 << 13;
/// Statusword bit 13 in homing mode: homing error.
pub const HOMING_ERROR: u16 = 1 << 13;
/// The mode-specific statusword bits above, together.
pub const MODE_STATUS: u16 = TARGET_REACHED | SET_POINT_ACKNOWLEDGE | FOLLOWING_ERROR;
