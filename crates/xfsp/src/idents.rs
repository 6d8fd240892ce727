//! The parameter table of §3.4: every ident the draft defines, with its name, what
//! the unit and subunit fields mean for it, and its format.
//!
//! Readings (note 5): MUX is written `%x00.29` and APPSTAT `%x00.00.00.81`; both are
//! read as the hex digits run together (0x29 and 0x81), which also fits their place
//! in the otherwise sequential table. AOA and AOAR are both `%x00.00.77` in the
//! draft. That is a genuine clash, so the table keeps both and a parameter is
//! identified by ident *and* format together ([`lookup`]): 0x77 with SINT is AOA,
//! 0x77 with RANGE is AOAR.
//!
//! The table was transcribed from the draft mechanically; the test at the bottom
//! re-reads the copy of the draft the repository carries, `spec/xfsp-draft-00.txt` (in this crate),
//! and checks it entry by entry.

use super::format::FormatId;

/// A 20-bit parameter identifier (§3.2 `Ident`, values in §3.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Ident(pub u32);

impl std::fmt::Display for Ident {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match name(*self) {
            Some(n) => write!(f, "{n}"),
            None => write!(f, "ident {:#x}", self.0),
        }
    }
}

/// One row of the §3.4 table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IdentInfo {
    /// §3.4 "Parameter ID", 20 bits.
    pub ident: Ident,
    /// The draft's name, e.g. `"P-ALT"`.
    pub name: &'static str,
    /// The draft's short description.
    pub description: &'static str,
    /// "Unit Usage" as the draft words it.
    pub unit: &'static str,
    /// "SubUnit Usage" as the draft words it.
    pub subunit: &'static str,
    /// §3.4 "Format": the attribute format (§3.3).
    pub format: FormatId,
}

/// The row for a parameter seen on the wire. Ident and format together, because
/// the draft gives AOA (SINT) and AOAR (RANGE) the same ident.
pub fn lookup(ident: Ident, format: FormatId) -> Option<&'static IdentInfo> {
    PARAMS
        .iter()
        .find(|p| p.ident == ident && p.format == format)
}

/// The first row with this ident, whatever its format (for AOA/AOAR, the first).
pub fn lookup_ident(ident: Ident) -> Option<&'static IdentInfo> {
    PARAMS.iter().find(|p| p.ident == ident)
}

/// The row with this name (exact, as the draft spells it).
pub fn by_name(name: &str) -> Option<&'static IdentInfo> {
    PARAMS.iter().find(|p| p.name == name)
}

/// The draft's name for an ident, if it has one.
pub fn name(ident: Ident) -> Option<&'static str> {
    lookup_ident(ident).map(|p| p.name)
}

/// GOAROUND: Go around requested
pub const GOAROUND: Ident = Ident(0x00);
/// P-ALT: Pressure Altitude
pub const P_ALT: Ident = Ident(0x01);
/// T-ALT: True Altitude
pub const T_ALT: Ident = Ident(0x02);
/// IAS: Indicated Airspeed
pub const IAS: Ident = Ident(0x03);
/// CAS: Calibrated Airspeed
pub const CAS: Ident = Ident(0x04);
/// CASMSG: Crew Alerting System Message
pub const CASMSG: Ident = Ident(0x05);
/// THROTPOS: Throttle position
pub const THROTPOS: Ident = Ident(0x06);
/// INAIR: Are we in the air (vs. on the ground)
pub const INAIR: Ident = Ident(0x07);
/// BARO: Current barometric setting
pub const BARO: Ident = Ident(0x08);
/// CLTPOS: Collective Position
pub const CLTPOS: Ident = Ident(0x09);
/// CLTPOSREQ: A/P Requested Collective Position
pub const CLTPOSREQ: Ident = Ident(0x0a);
/// MAGHDG: Magnetic Heading
pub const MAGHDG: Ident = Ident(0x0b);
/// MAGCRS: Magnetic Course (via RNAV)
pub const MAGCRS: Ident = Ident(0x0c);
/// TRUECRS: True Course (via RNAV)
pub const TRUECRS: Ident = Ident(0x0d);
/// MAGDTK: Desired Course (via RNAV)
pub const MAGDTK: Ident = Ident(0x0e);
/// TRUEDTK: Desired course (via RNAV)
pub const TRUEDTK: Ident = Ident(0x0f);
/// LAT: Current position latitude
pub const LAT: Ident = Ident(0x10);
/// LON: Current position longitude
pub const LON: Ident = Ident(0x11);
/// RNAVALT: Altitude measured by RNAV
pub const RNAVALT: Ident = Ident(0x12);
/// ROLL: Current degrees of roll, -18000 being being upside down towards left, 18000 being upside down to the right
pub const ROLL: Ident = Ident(0x13);
/// PITCH: Current degrees of pitch, 9000 being straight up, -9000 being straight down
pub const PITCH: Ident = Ident(0x14);
/// YAW: Yaw/Inclination as measured in G force
pub const YAW: Ident = Ident(0x15);
/// FUELTOT: Computed remaining fuel (divisor may be overridden by fuel type in FUELLEVLR)
pub const FUELTOT: Ident = Ident(0x16);
/// RNAVHFOM: Horizontal Figure of Merit
pub const RNAVHFOM: Ident = Ident(0x17);
/// RNAVVFOM: Vertical Figure of Merit
pub const RNAVVFOM: Ident = Ident(0x18);
/// RNAVHPL: Horizontal Protection Level
pub const RNAVHPL: Ident = Ident(0x19);
/// RNAVVPL: Vertical Protection Level
pub const RNAVVPL: Ident = Ident(0x1a);
/// IASRT: Indicated Airspeed Rate of Change
pub const IASRT: Ident = Ident(0x1b);
/// KBDSEL: Activate the named on-screen keyboard or none if empty
pub const KBDSEL: Ident = Ident(0x1c);
/// KEYPRESS: Send the FMS encoded key press to the given display
pub const KEYPRESS: Ident = Ident(0x1d);
/// SURFPOS: Position of arbitrary control surface
pub const SURFPOS: Ident = Ident(0x1e);
/// SURFREQ: Requested control surface position
pub const SURFREQ: Ident = Ident(0x1f);
/// SURFTORQUE: Aerodynamic torque applied to a control surface relative to movement
pub const SURFTORQUE: Ident = Ident(0x20);
/// SURFFORCE: Aerodynamic force applied to a control surface relative to movement
pub const SURFFORCE: Ident = Ident(0x21);
/// WINDSPD: Wind Speed
pub const WINDSPD: Ident = Ident(0x22);
/// WINDBRG: True Bearing from which wind blows
pub const WINDBRG: Ident = Ident(0x23);
/// COMFREQKHZ: Communication Frequency
pub const COMFREQKHZ: Ident = Ident(0x24);
/// NAVFREQKHZ: Navigation Frequency
pub const NAVFREQKHZ: Ident = Ident(0x25);
/// COMVOL: Communication Volume (0-100)
pub const COMVOL: Ident = Ident(0x26);
/// NAVVOL: Communication Volume (0-100)
pub const NAVVOL: Ident = Ident(0x27);
/// COMSQL: Communication Squelch (0-100)
pub const COMSQL: Ident = Ident(0x28);
/// MUX: Selected multiplexer input or output
pub const MUX: Ident = Ident(0x29);
/// ICSVOL: Intercom Volume (0-100)
pub const ICSVOL: Ident = Ident(0x2a);
/// COMSTATE: COM radio state
pub const COMSTATE: Ident = Ident(0x2b);
/// ICSRXCOMS: Which COM Radios to Monitor (mask)
pub const ICSRXCOMS: Ident = Ident(0x2c);
/// ICSRXNAVS: Which NAV Radios to Monitor (mask)
pub const ICSRXNAVS: Ident = Ident(0x2d);
/// ICSMODE: Intercom Mode
pub const ICSMODE: Ident = Ident(0x2e);
/// ICSTXCOMS: Which COM Radios to Transmit (mask)
pub const ICSTXCOMS: Ident = Ident(0x2f);
/// DATE: Date in YYYY-MM-DD format
pub const DATE: Ident = Ident(0x30);
/// GLOAD: Current Normal to Aircraft Loading
pub const GLOAD: Ident = Ident(0x31);
/// RATEOFTURN: Turn Coordinator Rate Per Second
pub const RATEOFTURN: Ident = Ident(0x32);
/// GROUNDSPEED: Groundspeed
pub const GROUNDSPEED: Ident = Ident(0x33);
/// VSPEED: Vertical speed
pub const VSPEED: Ident = Ident(0x34);
/// XPDRIDENT: XPDR Ident request (USERSELECT only). Non-standby transponders must IDENT regardless of UNIT. Used only to request IDENT, but IDENT state reported in XPDRMODE
pub const XPDRIDENT: Ident = Ident(0x35);
/// XPDRRPS: XPDR Replies per second (normalized)
pub const XPDRRPS: Ident = Ident(0x36);
/// XPDRSQUAWK: XPDR Squawk as decimal integer (e.g., 1200). All transponders must change SQUAWK regardless of UNIT
pub const XPDRSQUAWK: Ident = Ident(0x37);
/// XPDRMODE: XPDR Mode. Note that IDENT flag is ignored in USERSELECT condition.
pub const XPDRMODE: Ident = Ident(0x38);
/// NAVOBS: NAV OBS Value
pub const NAVOBS: Ident = Ident(0x39);
/// NAVBRG: Bearing to nav aid
pub const NAVBRG: Ident = Ident(0x3a);
/// NAVCDI: Course Deviation (-1000 to 1000)
pub const NAVCDI: Ident = Ident(0x3b);
/// NAVGSI: Glide Slope (-1000 to 1000)
pub const NAVGSI: Ident = Ident(0x3c);
/// NAVFLAGS: Navigation Flags (see XFS_NAV_FLAG_*
pub const NAVFLAGS: Ident = Ident(0x3d);
/// FLAPREQ: Requested Flap Position 0 = up, 100000 = fully down, -100000 is fully negative
pub const FLAPREQ: Ident = Ident(0x3e);
/// FLAPPOS: Flap actuator position, 0 = up, 100000 = fully down, -100000 is fully negative
pub const FLAPPOS: Ident = Ident(0x3f);
/// ECBSTAT: ECB Status change or request, see xfs_ecb.h
pub const ECBSTAT: Ident = Ident(0x40);
/// PTRIMREQ: Requested Pitch Trim Position (negative nose down, 0 neutral, positive nose up)
pub const PTRIMREQ: Ident = Ident(0x41);
/// PTRIMPOS: Pitch Trim Position (negative nose down, 0 neutral, positive nose up)
pub const PTRIMPOS: Ident = Ident(0x42);
/// RTRIMREQ: Requested Roll Trim Position (negative left bank, 0 neutral, positive right bank)
pub const RTRIMREQ: Ident = Ident(0x43);
/// RTRIMPOS: Roll Trim Position (negative left bank, 0 neutral, positive right bank)
pub const RTRIMPOS: Ident = Ident(0x44);
/// BUSSTAT: Status of Bus
pub const BUSSTAT: Ident = Ident(0x45);
/// TEMP: Arbitrary Temperature in a location
pub const TEMP: Ident = Ident(0x46);
/// TAS: True Airspeed
pub const TAS: Ident = Ident(0x47);
/// TAT: Total Air Temperature
pub const TAT: Ident = Ident(0x48);
/// OAT: Outside Air Temperature accounting for compressibility
pub const OAT: Ident = Ident(0x49);
/// D-ALT: Density Altitude
pub const D_ALT: Ident = Ident(0x4a);
/// OILPRES: Oil Pressure
pub const OILPRES: Ident = Ident(0x4b);
/// OILTEMP: Oil Temp
pub const OILTEMP: Ident = Ident(0x4c);
/// XFDFPS: XFD Display Frames Per Second (FPS)
pub const XFDFPS: Ident = Ident(0x4d);
/// TIREPRES: Tire Pressure
pub const TIREPRES: Ident = Ident(0x4e);
/// CHT: Cylinder Head Temperature
pub const CHT: Ident = Ident(0x4f);
/// EGT: Exhaust Gas Temperature
pub const EGT: Ident = Ident(0x50);
/// COOLTEMP: Coolant Temperature
pub const COOLTEMP: Ident = Ident(0x51);
/// FUELFLOW: Fuel Flow
pub const FUELFLOW: Ident = Ident(0x52);
/// FUELPRES: Fuel Pressure
pub const FUELPRES: Ident = Ident(0x53);
/// FUELLEVL: Fuel Level (divisor may be overridden by fuel type)
pub const FUELLEVL: Ident = Ident(0x54);
/// MANPRES: Manifold pressure
pub const MANPRES: Ident = Ident(0x55);
/// ENGRPM: Engine RPM
pub const ENGRPM: Ident = Ident(0x56);
/// PROPRPM: Propeller RPM
pub const PROPRPM: Ident = Ident(0x57);
/// MACH: Mach
pub const MACH: Ident = Ident(0x58);
/// IASBUG: Target indicated airspeed
pub const IASBUG: Ident = Ident(0x59);
/// HDGBUG: Bugged Magnetic Heading
pub const HDGBUG: Ident = Ident(0x5a);
/// ALTBUG: Bugged Altitude
pub const ALTBUG: Ident = Ident(0x5b);
/// WAYPOINT: A way point in a flight plan, subunit is position in flightplan, beginning with 1 for first waypoint. Subunit 0 is only used to indicate an empty flight plan.
pub const WAYPOINT: Ident = Ident(0x5c);
/// INSERT: Insert A way point in a flight plan, subunit is position in flightplan which it should become (SYSSEL/USERSEL ONLY)
pub const INSERT: Ident = Ident(0x5d);
/// DELETE: Delete A way point in a flight plan, subunit is position in flightplan starting at 1 (SYSSEL/USERSEL ONLY). Label must match
pub const DELETE: Ident = Ident(0x5e);
/// NOTE: Notation of something important within the quick access log or bus
pub const NOTE: Ident = Ident(0x5f);
/// NAVGPS: GPS Mode
pub const NAVGPS: Ident = Ident(0x60);
/// NAVDIS: Distance to next or last waypoint or DME for VOR/ILS/etc
pub const NAVDIS: Ident = Ident(0x61);
/// NAVXTK: Cross track error (negative is left)
pub const NAVXTK: Ident = Ident(0x62);
/// NAVETE: Time to next or last waypoint
pub const NAVETE: Ident = Ident(0x63);
/// BRIGHTNESS: Universal display brightness (0-1000 for night time mode, 1000-2000 for daytime modes
pub const BRIGHTNESS: Ident = Ident(0x64);
/// MANTEMP: Manifold temperature
pub const MANTEMP: Ident = Ident(0x65);
/// DIRECT: Go direct to a way point in a flight plan, subunit is position in flightplan starting at 1 (SYSSEL/USERSEL ONLY). Label must match
pub const DIRECT: Ident = Ident(0x66);
/// ACTIVATE: Activate leg terminating at way point in a flight plan, subunit is position in flightplan (SYSSEL/USERSEL ONLY). Label must match
pub const ACTIVATE: Ident = Ident(0x67);
/// MMPARAM: Moving Map parameters. Subunit is one of XFS_MM_PARAM_*
pub const MMPARAM: Ident = Ident(0x68);
/// SERVOREQ: Requested servo position and state
pub const SERVOREQ: Ident = Ident(0x69);
/// SERVOPOS: Current servo actuator position
pub const SERVOPOS: Ident = Ident(0x6a);
/// SONICHAT: Ultrasonic rangefinder height above terrain
pub const SONICHAT: Ident = Ident(0x6b);
/// LIDARHAT: LIDAR rangefinder height above terrain
pub const LIDARHAT: Ident = Ident(0x6c);
/// RADARHAT: Radar rangefinder height above terrain
pub const RADARHAT: Ident = Ident(0x6d);
/// HAT: Computed height above terrain
pub const HAT: Ident = Ident(0x6e);
/// COMSTANDBY: Standby COM Frequency (same rules and range as COMFREQKHZ)
pub const COMSTANDBY: Ident = Ident(0x6f);
/// NAVSTANDBY: Standby NAV Frequency (same rules and range as NAVFREQKHZ)
pub const NAVSTANDBY: Ident = Ident(0x70);
/// STALLSPEED: Estimated real-time Stall speed
pub const STALLSPEED: Ident = Ident(0x71);
/// TIMEMS: Time in milliseconds from midnight zulu time
pub const TIMEMS: Ident = Ident(0x72);
/// YTRIMREQ: Requested Yaw Trim Position (negative left, 0 neutral, positive right)
pub const YTRIMREQ: Ident = Ident(0x73);
/// YTRIMPOS: Yaw Trim Position (negative left, 0 neutral, positive right)
pub const YTRIMPOS: Ident = Ident(0x74);
/// VSPEEDBUG: Vertical speed bug in fpm
pub const VSPEEDBUG: Ident = Ident(0x75);
/// MUSICSRC: Music Source (0 = none)
pub const MUSICSRC: Ident = Ident(0x76);
/// AOA: Angle of attack as an actual angle
pub const AOA: Ident = Ident(0x77);
/// AOAR: Angle of attack range -- should contain green (beginning of approach range), white (reference angle), yellow (approaching stall) and a red (imminent stall)
pub const AOAR: Ident = Ident(0x77);
/// GPIO: GPIO Input/Output
pub const GPIO: Ident = Ident(0x78);
/// ANALOG: Raw Analog value 0-4095
pub const ANALOG: Ident = Ident(0x79);
/// PWM: PWM value 0-4095 -- subunit is port number, 1-8
pub const PWM: Ident = Ident(0x7a);
/// XPDRACID: ICAO 24-bit Aircraft Identifier
pub const XPDRACID: Ident = Ident(0x7b);
/// XPDRFLID: Up to 8-character, NULL terminated flight ID
pub const XPDRFLID: Ident = Ident(0x7c);
/// THROTREQ: Requested throttle position
pub const THROTREQ: Ident = Ident(0x7d);
/// RPMREQ: Prop governor requested RPM
pub const RPMREQ: Ident = Ident(0x7e);
/// TACHTIME: Tachometer time, unit is engine
pub const TACHTIME: Ident = Ident(0x7f);
/// TOTTIME: Total aircraft time
pub const TOTTIME: Ident = Ident(0x80);
/// APPSTAT: Application Status / Requests
pub const APPSTAT: Ident = Ident(0x81);
/// CDINAVSRC: Select index (> 0) of CDI NAV Source or 0 for none
pub const CDINAVSRC: Ident = Ident(0x82);
/// BRGNAVSRC: Select index (> 0) CDI BRG Source or 0 for none
pub const BRGNAVSRC: Ident = Ident(0x83);
/// COMSEL: Select COM Radio for Tuning
pub const COMSEL: Ident = Ident(0x84);
/// NAVSEL: Select NAV Radio for Tuning
pub const NAVSEL: Ident = Ident(0x85);
/// MSTRCAUTN: Master Caution Active when true. Resets by SYSSEL/ USERSEL with value of FALSE
pub const MSTRCAUTN: Ident = Ident(0x86);
/// MSTRWARN: Master Warning Active when true. Resets by SYSSEL/ USERSEL with value of FALSE
pub const MSTRWARN: Ident = Ident(0x87);
/// ROLLRT: Rate of change of about A/C longitudinal axis (P)
pub const ROLLRT: Ident = Ident(0x88);
/// PITCHRT: Rate of change about A/C transverse axis (Q)
pub const PITCHRT: Ident = Ident(0x89);
/// YAWRT: Rate of change about A/C vertical axis (R)
pub const YAWRT: Ident = Ident(0x8a);
/// STKPITCH: Stick Pitch Position (negative nose down, 0 neutral, positive nose up)
pub const STKPITCH: Ident = Ident(0x8b);
/// STKROLL: Stick Roll Position (negative left bank, 0 neutral, positive right bank)
pub const STKROLL: Ident = Ident(0x8c);
/// STKYAW: Pedal Yaw Position (negative left, 0 neutral, positive right)
pub const STKYAW: Ident = Ident(0x8d);
/// BATTTEMP: Battery Temp
pub const BATTTEMP: Ident = Ident(0x8e);
/// MOTORTEMP: Motor Temp
pub const MOTORTEMP: Ident = Ident(0x8f);
/// POWERTEMP: Temp of a device supplying/converting power to a propulsion system
pub const POWERTEMP: Ident = Ident(0x90);
/// TORQUE: Torque
pub const TORQUE: Ident = Ident(0x91);
/// TAILNUM: Up to 8-character, NULL terminated tail number
pub const TAILNUM: Ident = Ident(0x92);
/// ROLLREQ: F/D requested degrees of roll in 100 * degrees with 0 being right side up, -18000 being being upside down towards left, 18000 being upside down to the right
pub const ROLLREQ: Ident = Ident(0x93);
/// PITCHREQ: F/D requested degrees of pitch in 100 * degrees with 0 being straight ahead, 9000 being straight up, -9000 being straight down
pub const PITCHREQ: Ident = Ident(0x94);
/// YAWREQ: F/D requested G force of inclination with 0 being no yaw
pub const YAWREQ: Ident = Ident(0x95);
/// STKPITCHREQ: A/P Requested Stick Pitch Position (negative nose down, 0 neutral, positive nose up)
pub const STKPITCHREQ: Ident = Ident(0x96);
/// STKROLLREQ: A/P Requested Stick Roll Position (negative left bank, 0 neutral, positive right bank)
pub const STKROLLREQ: Ident = Ident(0x97);
/// STKYAWREQ: A/P Requested Pedal Yaw Position (negative left, 0 neutral, positive right)
pub const STKYAWREQ: Ident = Ident(0x98);
/// FDMODEACT: Active Flight Director Modes
pub const FDMODEACT: Ident = Ident(0x99);
/// FDMODEARM: Armed Flight Director Modes (XFS_AFCS_FD_MODE_*
pub const FDMODEARM: Ident = Ident(0x9a);
/// ALTHOLDBUG: Altitude used by FD for altitude hold
pub const ALTHOLDBUG: Ident = Ident(0x9b);
/// APMODE: Autopilot Modes
pub const APMODE: Ident = Ident(0x9c);
/// ICSSQL: Intercom Squelch (0-100)
pub const ICSSQL: Ident = Ident(0x9d);
/// PITCHBUG: Target pitch
pub const PITCHBUG: Ident = Ident(0x9e);
/// PTSPEED: Power Turbine Speed (commonly N1)
pub const PTSPEED: Ident = Ident(0x9f);
/// GTSPEED: Gas Turbine Speed (commonly N2 or Ng)
pub const GTSPEED: Ident = Ident(0xa0);
/// TIT: Turbine Inlet Temperature
pub const TIT: Ident = Ident(0xa1);
/// ITT: Inter-Turbine Temperature
pub const ITT: Ident = Ident(0xa2);
/// POWER: Power under current engine and environmental conditions relative to engine design maximum
pub const POWER: Ident = Ident(0xa3);
/// ENGSTATUS: Engine specific set of flags or values
pub const ENGSTATUS: Ident = Ident(0xa4);
/// CABINALT: Cabin Equivalent Altitude
pub const CABINALT: Ident = Ident(0xa5);
/// CABINALTREQ: Cabin Equivalent Altitude
pub const CABINALTREQ: Ident = Ident(0xa6);
/// DIFFPRES: Differential Pressure
pub const DIFFPRES: Ident = Ident(0xa7);
/// DIFFPRESREQ: Requested Differential Pressure
pub const DIFFPRESREQ: Ident = Ident(0xa8);
/// FUELTEMP: Arbitrary Temperature in a location
pub const FUELTEMP: Ident = Ident(0xa9);
/// ENGSTATE: Engine operating state
pub const ENGSTATE: Ident = Ident(0xaa);
/// ENGSTATEREQ: Requested Engine operating state
pub const ENGSTATEREQ: Ident = Ident(0xab);
/// BLEEDAIR: Bleed Air Level (Percent of Max)
pub const BLEEDAIR: Ident = Ident(0xac);
/// BLEEDAIRREQ: Requested Bleed Air Level
pub const BLEEDAIRREQ: Ident = Ident(0xad);
/// LIGHTING: Lighting Color/Level
pub const LIGHTING: Ident = Ident(0xae);
/// LIGHTINGREQ: Requested Lighting Color/Level
pub const LIGHTINGREQ: Ident = Ident(0xaf);
/// ICING: Deicing State
pub const ICING: Ident = Ident(0xb0);
/// ICINGREQ: Requested Deicing State
pub const ICINGREQ: Ident = Ident(0xb1);
/// LDGGEAR: Landing Gear State
pub const LDGGEAR: Ident = Ident(0xb2);
/// LDGGEARREQ: Landing Gear State
pub const LDGGEARREQ: Ident = Ident(0xb3);
/// CABINTEMP: Cabin Temperature in a zone
pub const CABINTEMP: Ident = Ident(0xb4);
/// CABINTEMPREQ: Requested Cabin Temperature in a zone
pub const CABINTEMPREQ: Ident = Ident(0xb5);
/// CHKLIST: Checklist Item
pub const CHKLIST: Ident = Ident(0xb6);
/// WBRANGE: Weight and envelope per configuration
pub const WBRANGE: Ident = Ident(0xb7);
/// WBSTARM: Arm for given station
pub const WBSTARM: Ident = Ident(0xb8);
/// WBSTMAXWEIGHT: Maximum weight at given station
pub const WBSTMAXWEIGHT: Ident = Ident(0xb9);
/// WBSTFLAGS: Flags about given station
pub const WBSTFLAGS: Ident = Ident(0xba);
/// WBSTWEIGHT: Actual weight at given station
pub const WBSTWEIGHT: Ident = Ident(0xbb);
/// TASEFF: Fuel Economy Relative to True Airspeed
pub const TASEFF: Ident = Ident(0xbc);
/// GSEFF: Fuel Economy Relative to Groundspeed
pub const GSEFF: Ident = Ident(0xbd);
/// TIMETOEMPTY: Time to Empty
pub const TIMETOEMPTY: Ident = Ident(0xbe);
/// DISTTOEMPTY: Distance to Empty
pub const DISTTOEMPTY: Ident = Ident(0xbf);
/// FLIGHTSTATE: State of Flight
pub const FLIGHTSTATE: Ident = Ident(0xc0);
/// UPDATESTATE: Status of any update
pub const UPDATESTATE: Ident = Ident(0xc1);
/// TORQUEREQ: Requested Torque
pub const TORQUEREQ: Ident = Ident(0xc2);
/// STKPITCHFRCE: Stick Pitch Force applied by the pilot, positive value - push, negative value - pull
pub const STKPITCHFRCE: Ident = Ident(0xc3);
/// STKROLLFRCE: Stick Roll Force applied by the pilot, positive value - roll right, negative value - roll left
pub const STKROLLFRCE: Ident = Ident(0xc4);
/// STKYAWFRCE: Pedal Yaw Force applied by the pilot, positive value - right rudder, negative value - left rudder
pub const STKYAWFRCE: Ident = Ident(0xc5);
/// APPITCHFRCE: Auto Pilot Pitch Force exerted on control surfaces, positive value - push, negative value - pull
pub const APPITCHFRCE: Ident = Ident(0xc6);
/// APROLLFRCE: Auto Pilot Roll Force exerted on control surfaces, positive value - roll right, negative value - roll left
pub const APROLLFRCE: Ident = Ident(0xc7);
/// APYAWFRCE: Auto Pilot Yaw Force exerted on control surfaces, positive value - right rudder, negative value - left rudder
pub const APYAWFRCE: Ident = Ident(0xc8);
/// EFBPARAM: Up to 64-character, NULL terminated parameter value
pub const EFBPARAM: Ident = Ident(0xc9);
/// OILPRESCOMP: Compensated Oil Pressure
pub const OILPRESCOMP: Ident = Ident(0xca);
/// MACHBUG: Target Mach
pub const MACHBUG: Ident = Ident(0xcb);
/// AOART: Angle of attack rate of change
pub const AOART: Ident = Ident(0xcc);
/// TASBUG: Target true airspeed
pub const TASBUG: Ident = Ident(0xcd);
/// GSBUG: Target groundspeed
pub const GSBUG: Ident = Ident(0xce);
/// AOABUG: Bugged AOA
pub const AOABUG: Ident = Ident(0xcf);
/// ECUTIME: ECU Hours
pub const ECUTIME: Ident = Ident(0xd1);
/// DBASE: Active database information
pub const DBASE: Ident = Ident(0xd2);
/// EAS: Equivalent Airspeed
pub const EAS: Ident = Ident(0xd3);
/// EASRT: Equivalent Airspeed Rate of Change
pub const EASRT: Ident = Ident(0xd4);
/// EASBUG: Target equivalent airspeed
pub const EASBUG: Ident = Ident(0xd5);
/// POWERREQ: Requested power as percent of engine design maximum
pub const POWERREQ: Ident = Ident(0xd6);
/// BRAKE: Wheel brake status
pub const BRAKE: Ident = Ident(0xd7);
/// BRAKEREQ: Amount of brake requested
pub const BRAKEREQ: Ident = Ident(0xd8);
/// NAVSQL: Communication Squelch (0-100)
pub const NAVSQL: Ident = Ident(0xd9);
/// STATIONID: VOR Station ID decoded from Morse code
pub const STATIONID: Ident = Ident(0xda);
/// SVPARAM: Synthetic Vision parameters. Subunit is one of XFS_SV_PARAM_*
pub const SVPARAM: Ident = Ident(0xdb);
/// FDCDISEL: Global selection of which CDI the flight director should track
pub const FDCDISEL: Ident = Ident(0xdc);
/// BLOODOXY: Blood oxygen level of given seat occupant
pub const BLOODOXY: Ident = Ident(0xdd);
/// PULSE: Pulse rate of given seat occupant
pub const PULSE: Ident = Ident(0xde);
/// BREATHS: Breathing rate of given seat occupant
pub const BREATHS: Ident = Ident(0xdf);
/// CARBMONOX: Carbon Monoxide levels detected by sensor
pub const CARBMONOX: Ident = Ident(0xe0);
/// FLOWRATE: Oxygen flow rate
pub const FLOWRATE: Ident = Ident(0xe1);
/// TANKPRES: Oxygen tank pressure
pub const TANKPRES: Ident = Ident(0xe2);
/// RNAVVS: Vertical speed computed from RNAV
pub const RNAVVS: Ident = Ident(0xe3);
/// COMPRESET: Selected COM Radio Preset (0=Non-preset frequency)
pub const COMPRESET: Ident = Ident(0xe4);
/// COMNAME: Name of COM Radio or Preset Frequency
pub const COMNAME: Ident = Ident(0xe5);
/// NAVPRESET: Selected NAV Radio Preset (0=Non-preset frequency)
pub const NAVPRESET: Ident = Ident(0xe6);
/// NAVNAME: Name of NAV Radio or Preset Frequency
pub const NAVNAME: Ident = Ident(0xe7);
/// VNORTH: North component of velocity in true world coordinates
pub const VNORTH: Ident = Ident(0xe8);
/// VEAST: East component of velocity in true world coordinates
pub const VEAST: Ident = Ident(0xe9);
/// ENGPOWER: Current Engine Power
pub const ENGPOWER: Ident = Ident(0xea);
/// CHARGE: Measured remaining battery charge
pub const CHARGE: Ident = Ident(0xeb);
/// CHARGETOT: Computed remaining charge
pub const CHARGETOT: Ident = Ident(0xec);

/// Every parameter of §3.4, in the draft's order.
pub static PARAMS: &[IdentInfo] = &[
    IdentInfo {
        ident: Ident(0x00),
        name: "GOAROUND",
        description: "Go around requested",
        unit: "None",
        subunit: "None",
        format: FormatId::Bool,
    },
    IdentInfo {
        ident: Ident(0x01),
        name: "P-ALT",
        description: "Pressure Altitude",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x02),
        name: "T-ALT",
        description: "True Altitude",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x03),
        name: "IAS",
        description: "Indicated Airspeed",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x04),
        name: "CAS",
        description: "Calibrated Airspeed",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x05),
        name: "CASMSG",
        description: "Crew Alerting System Message",
        unit: "CAS System ID",
        subunit: "None",
        format: FormatId::CasMsg,
    },
    IdentInfo {
        ident: Ident(0x06),
        name: "THROTPOS",
        description: "Throttle position",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x07),
        name: "INAIR",
        description: "Are we in the air (vs. on the ground)",
        unit: "None",
        subunit: "None",
        format: FormatId::Bool,
    },
    IdentInfo {
        ident: Ident(0x08),
        name: "BARO",
        description: "Current barometric setting",
        unit: "None",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x09),
        name: "CLTPOS",
        description: "Collective Position",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x0a),
        name: "CLTPOSREQ",
        description: "A/P Requested Collective Position",
        unit: "None",
        subunit: "None",
        format: FormatId::Servo,
    },
    IdentInfo {
        ident: Ident(0x0b),
        name: "MAGHDG",
        description: "Magnetic Heading",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x0c),
        name: "MAGCRS",
        description: "Magnetic Course (via RNAV)",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x0d),
        name: "TRUECRS",
        description: "True Course (via RNAV)",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x0e),
        name: "MAGDTK",
        description: "Desired Course (via RNAV)",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x0f),
        name: "TRUEDTK",
        description: "Desired course (via RNAV)",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x10),
        name: "LAT",
        description: "Current position latitude",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x11),
        name: "LON",
        description: "Current position longitude",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x12),
        name: "RNAVALT",
        description: "Altitude measured by RNAV",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x13),
        name: "ROLL",
        description: "Current degrees of roll, -18000 being being upside down towards left, 18000 being upside down to the right",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x14),
        name: "PITCH",
        description: "Current degrees of pitch, 9000 being straight up, -9000 being straight down",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x15),
        name: "YAW",
        description: "Yaw/Inclination as measured in G force",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x16),
        name: "FUELTOT",
        description: "Computed remaining fuel (divisor may be overridden by fuel type in FUELLEVLR)",
        unit: "Fuel System ID/0=Sum of all",
        subunit: "0 = current total, 1 = total at end of flight",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x17),
        name: "RNAVHFOM",
        description: "Horizontal Figure of Merit",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x18),
        name: "RNAVVFOM",
        description: "Vertical Figure of Merit",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x19),
        name: "RNAVHPL",
        description: "Horizontal Protection Level",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x1a),
        name: "RNAVVPL",
        description: "Vertical Protection Level",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x1b),
        name: "IASRT",
        description: "Indicated Airspeed Rate of Change",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x1c),
        name: "KBDSEL",
        description: "Activate the named on-screen keyboard or none if empty",
        unit: "Display",
        subunit: "None",
        format: FormatId::String,
    },
    IdentInfo {
        ident: Ident(0x1d),
        name: "KEYPRESS",
        description: "Send the FMS encoded key press to the given display",
        unit: "Display",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x1e),
        name: "SURFPOS",
        description: "Position of arbitrary control surface",
        unit: "Surface Type",
        subunit: "Surface Type Subassembly",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x1f),
        name: "SURFREQ",
        description: "Requested control surface position",
        unit: "Surface Type",
        subunit: "Surface Type Subassembly",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x20),
        name: "SURFTORQUE",
        description: "Aerodynamic torque applied to a control surface relative to movement",
        unit: "Surface Type",
        subunit: "Surface Type Subassembly",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x21),
        name: "SURFFORCE",
        description: "Aerodynamic force applied to a control surface relative to movement",
        unit: "Surface Type",
        subunit: "Surface Type Subassembly",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x22),
        name: "WINDSPD",
        description: "Wind Speed",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x23),
        name: "WINDBRG",
        description: "True Bearing from which wind blows",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x24),
        name: "COMFREQKHZ",
        description: "Communication Frequency",
        unit: "Radio ID",
        subunit: "0=Radio /1+=Presets",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x25),
        name: "NAVFREQKHZ",
        description: "Navigation Frequency",
        unit: "Radio ID",
        subunit: "0=Radio /1+=Presets",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x26),
        name: "COMVOL",
        description: "Communication Volume (0-100)",
        unit: "Radio ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x27),
        name: "NAVVOL",
        description: "Communication Volume (0-100)",
        unit: "Radio ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x28),
        name: "COMSQL",
        description: "Communication Squelch (0-100)",
        unit: "Radio ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x29),
        name: "MUX",
        description: "Selected multiplexer input or output",
        unit: "MUX ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x2a),
        name: "ICSVOL",
        description: "Intercom Volume (0-100)",
        unit: "Audio Panel Unit",
        subunit: "0=System, 1=Pilot, 2=Copilot, rest are pax",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x2b),
        name: "COMSTATE",
        description: "COM radio state",
        unit: "Radio ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x2c),
        name: "ICSRXCOMS",
        description: "Which COM Radios to Monitor (mask)",
        unit: "Audio Panel Unit",
        subunit: "0=System, 1=Pilot, 2=Copilot, rest are pax",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x2d),
        name: "ICSRXNAVS",
        description: "Which NAV Radios to Monitor (mask)",
        unit: "Audio Panel Unit",
        subunit: "0=System, 1=Pilot, 2=Copilot, rest are pax",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x2e),
        name: "ICSMODE",
        description: "Intercom Mode",
        unit: "None",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x2f),
        name: "ICSTXCOMS",
        description: "Which COM Radios to Transmit (mask)",
        unit: "Audio Panel Unit",
        subunit: "0=System, 1=Pilot, 2=Copilot, rest are pax",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x30),
        name: "DATE",
        description: "Date in YYYY-MM-DD format",
        unit: "None",
        subunit: "None",
        format: FormatId::String,
    },
    IdentInfo {
        ident: Ident(0x31),
        name: "GLOAD",
        description: "Current Normal to Aircraft Loading",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x32),
        name: "RATEOFTURN",
        description: "Turn Coordinator Rate Per Second",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x33),
        name: "GROUNDSPEED",
        description: "Groundspeed",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x34),
        name: "VSPEED",
        description: "Vertical speed",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x35),
        name: "XPDRIDENT",
        description: "XPDR Ident request (USERSELECT only). Non-standby transponders must IDENT regardless of UNIT. Used only to request IDENT, but IDENT state reported in XPDRMODE",
        unit: "Always zero",
        subunit: "None",
        format: FormatId::Bool,
    },
    IdentInfo {
        ident: Ident(0x36),
        name: "XPDRRPS",
        description: "XPDR Replies per second (normalized)",
        unit: "XPDR ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x37),
        name: "XPDRSQUAWK",
        description: "XPDR Squawk as decimal integer (e.g., 1200). All transponders must change SQUAWK regardless of UNIT",
        unit: "XPDR ID (Rx Only) Zero for USERSELECT",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x38),
        name: "XPDRMODE",
        description: "XPDR Mode. Note that IDENT flag is ignored in USERSELECT condition.",
        unit: "XPDR ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x39),
        name: "NAVOBS",
        description: "NAV OBS Value",
        unit: "Radio/FMS ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x3a),
        name: "NAVBRG",
        description: "Bearing to nav aid",
        unit: "Radio/FMS ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x3b),
        name: "NAVCDI",
        description: "Course Deviation (-1000 to 1000)",
        unit: "Radio/FMS ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x3c),
        name: "NAVGSI",
        description: "Glide Slope (-1000 to 1000)",
        unit: "Radio/FMS ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x3d),
        name: "NAVFLAGS",
        description: "Navigation Flags (see XFS_NAV_FLAG_*",
        unit: "Radio/FMS ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x3e),
        name: "FLAPREQ",
        description: "Requested Flap Position 0 = up, 100000 = fully down, -100000 is fully negative",
        unit: "Actuator/0=Aircraft",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x3f),
        name: "FLAPPOS",
        description: "Flap actuator position, 0 = up, 100000 = fully down, -100000 is fully negative",
        unit: "Actuator/0=Aircraft",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x40),
        name: "ECBSTAT",
        description: "ECB Status change or request, see xfs_ecb.h",
        unit: "None",
        subunit: "None",
        format: FormatId::Bus,
    },
    IdentInfo {
        ident: Ident(0x41),
        name: "PTRIMREQ",
        description: "Requested Pitch Trim Position (negative nose down, 0 neutral, positive nose up)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x42),
        name: "PTRIMPOS",
        description: "Pitch Trim Position (negative nose down, 0 neutral, positive nose up)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x43),
        name: "RTRIMREQ",
        description: "Requested Roll Trim Position (negative left bank, 0 neutral, positive right bank)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x44),
        name: "RTRIMPOS",
        description: "Roll Trim Position (negative left bank, 0 neutral, positive right bank)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x45),
        name: "BUSSTAT",
        description: "Status of Bus",
        unit: "None",
        subunit: "None",
        format: FormatId::Bus,
    },
    IdentInfo {
        ident: Ident(0x46),
        name: "TEMP",
        description: "Arbitrary Temperature in a location",
        unit: "Location",
        subunit: "Sensor Number/0=Average",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x47),
        name: "TAS",
        description: "True Airspeed",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x48),
        name: "TAT",
        description: "Total Air Temperature",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x49),
        name: "OAT",
        description: "Outside Air Temperature accounting for compressibility",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x4a),
        name: "D-ALT",
        description: "Density Altitude",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x4b),
        name: "OILPRES",
        description: "Oil Pressure",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x4c),
        name: "OILTEMP",
        description: "Oil Temp",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x4d),
        name: "XFDFPS",
        description: "XFD Display Frames Per Second (FPS)",
        unit: "Display",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x4e),
        name: "TIREPRES",
        description: "Tire Pressure",
        unit: "Bogey",
        subunit: "Tire",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x4f),
        name: "CHT",
        description: "Cylinder Head Temperature",
        unit: "Engine",
        subunit: "Cylinder/0=Max",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x50),
        name: "EGT",
        description: "Exhaust Gas Temperature",
        unit: "Engine",
        subunit: "Cylinder/0=Max",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x51),
        name: "COOLTEMP",
        description: "Coolant Temperature",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x52),
        name: "FUELFLOW",
        description: "Fuel Flow",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x53),
        name: "FUELPRES",
        description: "Fuel Pressure",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x54),
        name: "FUELLEVL",
        description: "Fuel Level (divisor may be overridden by fuel type)",
        unit: "Fuel Tank ID/0=Sum of all",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x55),
        name: "MANPRES",
        description: "Manifold pressure",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x56),
        name: "ENGRPM",
        description: "Engine RPM",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x57),
        name: "PROPRPM",
        description: "Propeller RPM",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x58),
        name: "MACH",
        description: "Mach",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x59),
        name: "IASBUG",
        description: "Target indicated airspeed",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x5a),
        name: "HDGBUG",
        description: "Bugged Magnetic Heading",
        unit: "None",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x5b),
        name: "ALTBUG",
        description: "Bugged Altitude",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x5c),
        name: "WAYPOINT",
        description: "A way point in a flight plan, subunit is position in flightplan, beginning with 1 for first waypoint. Subunit 0 is only used to indicate an empty flight plan.",
        unit: "FMS ID",
        subunit: "None",
        format: FormatId::Waypoint,
    },
    IdentInfo {
        ident: Ident(0x5d),
        name: "INSERT",
        description: "Insert A way point in a flight plan, subunit is position in flightplan which it should become (SYSSEL/USERSEL ONLY)",
        unit: "FMS ID",
        subunit: "None",
        format: FormatId::Waypoint,
    },
    IdentInfo {
        ident: Ident(0x5e),
        name: "DELETE",
        description: "Delete A way point in a flight plan, subunit is position in flightplan starting at 1 (SYSSEL/USERSEL ONLY). Label must match",
        unit: "FMS ID",
        subunit: "None",
        format: FormatId::Waypoint,
    },
    IdentInfo {
        ident: Ident(0x5f),
        name: "NOTE",
        description: "Notation of something important within the quick access log or bus",
        unit: "None",
        subunit: "None",
        format: FormatId::String,
    },
    IdentInfo {
        ident: Ident(0x60),
        name: "NAVGPS",
        description: "GPS Mode",
        unit: "NAV radio unit or FMS Unit Number",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x61),
        name: "NAVDIS",
        description: "Distance to next or last waypoint or DME for VOR/ILS/etc",
        unit: "FMS Unit Number",
        subunit: "0 = next waypoint, 1 = last waypoint",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x62),
        name: "NAVXTK",
        description: "Cross track error (negative is left)",
        unit: "FMS Unit Number",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x63),
        name: "NAVETE",
        description: "Time to next or last waypoint",
        unit: "FMS Unit Number",
        subunit: "0 = next waypoint, 1 = last waypoint",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x64),
        name: "BRIGHTNESS",
        description: "Universal display brightness (0-1000 for night time mode, 1000-2000 for daytime modes",
        unit: "None",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x65),
        name: "MANTEMP",
        description: "Manifold temperature",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x66),
        name: "DIRECT",
        description: "Go direct to a way point in a flight plan, subunit is position in flightplan starting at 1 (SYSSEL/USERSEL ONLY). Label must match",
        unit: "None",
        subunit: "None",
        format: FormatId::Waypoint,
    },
    IdentInfo {
        ident: Ident(0x67),
        name: "ACTIVATE",
        description: "Activate leg terminating at way point in a flight plan, subunit is position in flightplan (SYSSEL/USERSEL ONLY). Label must match",
        unit: "None",
        subunit: "None",
        format: FormatId::Waypoint,
    },
    IdentInfo {
        ident: Ident(0x68),
        name: "MMPARAM",
        description: "Moving Map parameters. Subunit is one of XFS_MM_PARAM_*",
        unit: "MOVMAP ID",
        subunit: "XFS_MM_PARAM_*",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x69),
        name: "SERVOREQ",
        description: "Requested servo position and state",
        unit: "None",
        subunit: "None",
        format: FormatId::Servo,
    },
    IdentInfo {
        ident: Ident(0x6a),
        name: "SERVOPOS",
        description: "Current servo actuator position",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x6b),
        name: "SONICHAT",
        description: "Ultrasonic rangefinder height above terrain",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x6c),
        name: "LIDARHAT",
        description: "LIDAR rangefinder height above terrain",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x6d),
        name: "RADARHAT",
        description: "Radar rangefinder height above terrain",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x6e),
        name: "HAT",
        description: "Computed height above terrain",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x6f),
        name: "COMSTANDBY",
        description: "Standby COM Frequency (same rules and range as COMFREQKHZ)",
        unit: "Radio ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x70),
        name: "NAVSTANDBY",
        description: "Standby NAV Frequency (same rules and range as NAVFREQKHZ)",
        unit: "Radio ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x71),
        name: "STALLSPEED",
        description: "Estimated real-time Stall speed",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x72),
        name: "TIMEMS",
        description: "Time in milliseconds from midnight zulu time",
        unit: "None",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x73),
        name: "YTRIMREQ",
        description: "Requested Yaw Trim Position (negative left, 0 neutral, positive right)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x74),
        name: "YTRIMPOS",
        description: "Yaw Trim Position (negative left, 0 neutral, positive right)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x75),
        name: "VSPEEDBUG",
        description: "Vertical speed bug in fpm",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x76),
        name: "MUSICSRC",
        description: "Music Source (0 = none)",
        unit: "Audio Panel Unit",
        subunit: "0=System, 1=Pilot, 2=Copilot, rest are pax",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x77),
        name: "AOA",
        description: "Angle of attack as an actual angle",
        unit: "Source",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x77),
        name: "AOAR",
        description: "Angle of attack range -- should contain green (beginning of approach range), white (reference angle), yellow (approaching stall) and a red (imminent stall)",
        unit: "None",
        subunit: "None",
        format: FormatId::Range,
    },
    IdentInfo {
        ident: Ident(0x78),
        name: "GPIO",
        description: "GPIO Input/Output",
        unit: "I/O Module",
        subunit: "Module Port (0 or 1-8)",
        format: FormatId::Gpio,
    },
    IdentInfo {
        ident: Ident(0x79),
        name: "ANALOG",
        description: "Raw Analog value 0-4095",
        unit: "I/O Module",
        subunit: "Module Port (1-8)",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x7a),
        name: "PWM",
        description: "PWM value 0-4095 -- subunit is port number, 1-8",
        unit: "I/O Module",
        subunit: "Module Port (1-8)",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x7b),
        name: "XPDRACID",
        description: "ICAO 24-bit Aircraft Identifier",
        unit: "XPDR ID (Rx Only) Zero for USERSELECT",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x7c),
        name: "XPDRFLID",
        description: "Up to 8-character, NULL terminated flight ID",
        unit: "XPDR ID (Rx Only) Zero for USERSELECT",
        subunit: "None",
        format: FormatId::String,
    },
    IdentInfo {
        ident: Ident(0x7d),
        name: "THROTREQ",
        description: "Requested throttle position",
        unit: "None",
        subunit: "None",
        format: FormatId::Servo,
    },
    IdentInfo {
        ident: Ident(0x7e),
        name: "RPMREQ",
        description: "Prop governor requested RPM",
        unit: "None",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x7f),
        name: "TACHTIME",
        description: "Tachometer time, unit is engine",
        unit: "None",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x80),
        name: "TOTTIME",
        description: "Total aircraft time",
        unit: "None",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x81),
        name: "APPSTAT",
        description: "Application Status / Requests",
        unit: "CPU ID",
        subunit: "Process ID",
        format: FormatId::App,
    },
    IdentInfo {
        ident: Ident(0x82),
        name: "CDINAVSRC",
        description: "Select index (> 0) of CDI NAV Source or 0 for none",
        unit: "Display",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x83),
        name: "BRGNAVSRC",
        description: "Select index (> 0) CDI BRG Source or 0 for none",
        unit: "Display",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x84),
        name: "COMSEL",
        description: "Select COM Radio for Tuning",
        unit: "Display",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x85),
        name: "NAVSEL",
        description: "Select NAV Radio for Tuning",
        unit: "Display",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x86),
        name: "MSTRCAUTN",
        description: "Master Caution Active when true. Resets by SYSSEL/ USERSEL with value of FALSE",
        unit: "None",
        subunit: "None",
        format: FormatId::Bool,
    },
    IdentInfo {
        ident: Ident(0x87),
        name: "MSTRWARN",
        description: "Master Warning Active when true. Resets by SYSSEL/ USERSEL with value of FALSE",
        unit: "None",
        subunit: "None",
        format: FormatId::Bool,
    },
    IdentInfo {
        ident: Ident(0x88),
        name: "ROLLRT",
        description: "Rate of change of about A/C longitudinal axis (P)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x89),
        name: "PITCHRT",
        description: "Rate of change about A/C transverse axis (Q)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x8a),
        name: "YAWRT",
        description: "Rate of change about A/C vertical axis (R)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x8b),
        name: "STKPITCH",
        description: "Stick Pitch Position (negative nose down, 0 neutral, positive nose up)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x8c),
        name: "STKROLL",
        description: "Stick Roll Position (negative left bank, 0 neutral, positive right bank)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x8d),
        name: "STKYAW",
        description: "Pedal Yaw Position (negative left, 0 neutral, positive right)",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x8e),
        name: "BATTTEMP",
        description: "Battery Temp",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x8f),
        name: "MOTORTEMP",
        description: "Motor Temp",
        unit: "Motor",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x90),
        name: "POWERTEMP",
        description: "Temp of a device supplying/converting power to a propulsion system",
        unit: "Propulsion System",
        subunit: "Power converter/0=Max",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x91),
        name: "TORQUE",
        description: "Torque",
        unit: "Motor/Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x92),
        name: "TAILNUM",
        description: "Up to 8-character, NULL terminated tail number",
        unit: "None",
        subunit: "None",
        format: FormatId::String,
    },
    IdentInfo {
        ident: Ident(0x93),
        name: "ROLLREQ",
        description: "F/D requested degrees of roll in 100 * degrees with 0 being right side up, -18000 being being upside down towards left, 18000 being upside down to the right",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x94),
        name: "PITCHREQ",
        description: "F/D requested degrees of pitch in 100 * degrees with 0 being straight ahead, 9000 being straight up, -9000 being straight down",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x95),
        name: "YAWREQ",
        description: "F/D requested G force of inclination with 0 being no yaw",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x96),
        name: "STKPITCHREQ",
        description: "A/P Requested Stick Pitch Position (negative nose down, 0 neutral, positive nose up)",
        unit: "None",
        subunit: "None",
        format: FormatId::Servo,
    },
    IdentInfo {
        ident: Ident(0x97),
        name: "STKROLLREQ",
        description: "A/P Requested Stick Roll Position (negative left bank, 0 neutral, positive right bank)",
        unit: "None",
        subunit: "None",
        format: FormatId::Servo,
    },
    IdentInfo {
        ident: Ident(0x98),
        name: "STKYAWREQ",
        description: "A/P Requested Pedal Yaw Position (negative left, 0 neutral, positive right)",
        unit: "None",
        subunit: "None",
        format: FormatId::Servo,
    },
    IdentInfo {
        ident: Ident(0x99),
        name: "FDMODEACT",
        description: "Active Flight Director Modes",
        unit: "FD Number (0 for setting values)",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x9a),
        name: "FDMODEARM",
        description: "Armed Flight Director Modes (XFS_AFCS_FD_MODE_*",
        unit: "FD Number (0 for setting values)",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x9b),
        name: "ALTHOLDBUG",
        description: "Altitude used by FD for altitude hold",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x9c),
        name: "APMODE",
        description: "Autopilot Modes",
        unit: "AP Number (0 for setting value)",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x9d),
        name: "ICSSQL",
        description: "Intercom Squelch (0-100)",
        unit: "Audio Panel Unit",
        subunit: "0=System, 1=Pilot, 2=Copilot, rest are pax",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0x9e),
        name: "PITCHBUG",
        description: "Target pitch",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0x9f),
        name: "PTSPEED",
        description: "Power Turbine Speed (commonly N1)",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xa0),
        name: "GTSPEED",
        description: "Gas Turbine Speed (commonly N2 or Ng)",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xa1),
        name: "TIT",
        description: "Turbine Inlet Temperature",
        unit: "Engine",
        subunit: "Turbo/0=Max",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xa2),
        name: "ITT",
        description: "Inter-Turbine Temperature",
        unit: "Engine",
        subunit: "Sensor /0=Average",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xa3),
        name: "POWER",
        description: "Power under current engine and environmental conditions relative to engine design maximum",
        unit: "Motor/Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xa4),
        name: "ENGSTATUS",
        description: "Engine specific set of flags or values",
        unit: "Motor/Engine",
        subunit: "Engine Specific",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xa5),
        name: "CABINALT",
        description: "Cabin Equivalent Altitude",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xa6),
        name: "CABINALTREQ",
        description: "Cabin Equivalent Altitude",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xa7),
        name: "DIFFPRES",
        description: "Differential Pressure",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xa8),
        name: "DIFFPRESREQ",
        description: "Requested Differential Pressure",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xa9),
        name: "FUELTEMP",
        description: "Arbitrary Temperature in a location",
        unit: "Engine/Fuel Tank",
        subunit: "SubLocation /0=Average, 1=Sump",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xaa),
        name: "ENGSTATE",
        description: "Engine operating state",
        unit: "Motor/Engine",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xab),
        name: "ENGSTATEREQ",
        description: "Requested Engine operating state",
        unit: "Motor/Engine",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xac),
        name: "BLEEDAIR",
        description: "Bleed Air Level (Percent of Max)",
        unit: "Motor/Engine",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xad),
        name: "BLEEDAIRREQ",
        description: "Requested Bleed Air Level",
        unit: "Motor/Engine",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xae),
        name: "LIGHTING",
        description: "Lighting Color/Level",
        unit: "System",
        subunit: "Specific",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xaf),
        name: "LIGHTINGREQ",
        description: "Requested Lighting Color/Level",
        unit: "System",
        subunit: "Specific",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xb0),
        name: "ICING",
        description: "Deicing State",
        unit: "System/0=Aircraft",
        subunit: "Specific",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xb1),
        name: "ICINGREQ",
        description: "Requested Deicing State",
        unit: "System/0=Aircraft",
        subunit: "Specific",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xb2),
        name: "LDGGEAR",
        description: "Landing Gear State",
        unit: "Wheel/0=Aircraft",
        subunit: "Specific",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xb3),
        name: "LDGGEARREQ",
        description: "Landing Gear State",
        unit: "Wheel/0=Aircraft",
        subunit: "Specific",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xb4),
        name: "CABINTEMP",
        description: "Cabin Temperature in a zone",
        unit: "Zone",
        subunit: "Sensor Number /0=Average",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xb5),
        name: "CABINTEMPREQ",
        description: "Requested Cabin Temperature in a zone",
        unit: "Zone",
        subunit: "Sensor Number /0=Average",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xb6),
        name: "CHKLIST",
        description: "Checklist Item",
        unit: "Checklist Number",
        subunit: "Item Number /0=Title",
        format: FormatId::CasMsg,
    },
    IdentInfo {
        ident: Ident(0xb7),
        name: "WBRANGE",
        description: "Weight and envelope per configuration",
        unit: "None",
        subunit: "None",
        format: FormatId::WbRange,
    },
    IdentInfo {
        ident: Ident(0xb8),
        name: "WBSTARM",
        description: "Arm for given station",
        unit: "Configuration",
        subunit: "Station /0=total /1=total no fuel",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xb9),
        name: "WBSTMAXWEIGHT",
        description: "Maximum weight at given station",
        unit: "Configuration",
        subunit: "Station /0=total /1=total no fuel",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xba),
        name: "WBSTFLAGS",
        description: "Flags about given station",
        unit: "Configuration",
        subunit: "Station /0=total /1=total no fuel",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xbb),
        name: "WBSTWEIGHT",
        description: "Actual weight at given station",
        unit: "Configuration",
        subunit: "Station /0=total /1=total no fuel",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xbc),
        name: "TASEFF",
        description: "Fuel Economy Relative to True Airspeed",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xbd),
        name: "GSEFF",
        description: "Fuel Economy Relative to Groundspeed",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xbe),
        name: "TIMETOEMPTY",
        description: "Time to Empty",
        unit: "Engine /0=Aircraft",
        subunit: "0 - smoothed, without reserve, 1 - smoothed, with reserve, 2 - without reserve, 3 - with reserve",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xbf),
        name: "DISTTOEMPTY",
        description: "Distance to Empty",
        unit: "Engine /0=Aircraft",
        subunit: "0 - smoothed, without reserve, 1 - smoothed, with reserve, 2 - without reserve, 3 - with reserve",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xc0),
        name: "FLIGHTSTATE",
        description: "State of Flight",
        unit: "None",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xc1),
        name: "UPDATESTATE",
        description: "Status of any update",
        unit: "None",
        subunit: "None",
        format: FormatId::Update,
    },
    IdentInfo {
        ident: Ident(0xc2),
        name: "TORQUEREQ",
        description: "Requested Torque",
        unit: "Motor/Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xc3),
        name: "STKPITCHFRCE",
        description: "Stick Pitch Force applied by the pilot, positive value - push, negative value - pull",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xc4),
        name: "STKROLLFRCE",
        description: "Stick Roll Force applied by the pilot, positive value - roll right, negative value - roll left",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xc5),
        name: "STKYAWFRCE",
        description: "Pedal Yaw Force applied by the pilot, positive value - right rudder, negative value - left rudder",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xc6),
        name: "APPITCHFRCE",
        description: "Auto Pilot Pitch Force exerted on control surfaces, positive value - push, negative value - pull",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xc7),
        name: "APROLLFRCE",
        description: "Auto Pilot Roll Force exerted on control surfaces, positive value - roll right, negative value - roll left",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xc8),
        name: "APYAWFRCE",
        description: "Auto Pilot Yaw Force exerted on control surfaces, positive value - right rudder, negative value - left rudder",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xc9),
        name: "EFBPARAM",
        description: "Up to 64-character, NULL terminated parameter value",
        unit: "EFB ID",
        subunit: "XFS_EFB_PARAM_*",
        format: FormatId::String,
    },
    IdentInfo {
        ident: Ident(0xca),
        name: "OILPRESCOMP",
        description: "Compensated Oil Pressure",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xcb),
        name: "MACHBUG",
        description: "Target Mach",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xcc),
        name: "AOART",
        description: "Angle of attack rate of change",
        unit: "Source",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xcd),
        name: "TASBUG",
        description: "Target true airspeed",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xce),
        name: "GSBUG",
        description: "Target groundspeed",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xcf),
        name: "AOABUG",
        description: "Bugged AOA",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xd1),
        name: "ECUTIME",
        description: "ECU Hours",
        unit: "Engine",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xd2),
        name: "DBASE",
        description: "Active database information",
        unit: "CPU ID",
        subunit: "Process ID",
        format: FormatId::DBase,
    },
    IdentInfo {
        ident: Ident(0xd3),
        name: "EAS",
        description: "Equivalent Airspeed",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xd4),
        name: "EASRT",
        description: "Equivalent Airspeed Rate of Change",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xd5),
        name: "EASBUG",
        description: "Target equivalent airspeed",
        unit: "None",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xd6),
        name: "POWERREQ",
        description: "Requested power as percent of engine design maximum",
        unit: "Motor/Engine",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xd7),
        name: "BRAKE",
        description: "Wheel brake status",
        unit: "Left=1,Right=2,No direction=0",
        subunit: "Specific",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xd8),
        name: "BRAKEREQ",
        description: "Amount of brake requested",
        unit: "Left=1,Right=2,No direction=0",
        subunit: "Specific",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xd9),
        name: "NAVSQL",
        description: "Communication Squelch (0-100)",
        unit: "Radio ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xda),
        name: "STATIONID",
        description: "VOR Station ID decoded from Morse code",
        unit: "Radio ID",
        subunit: "None",
        format: FormatId::String,
    },
    IdentInfo {
        ident: Ident(0xdb),
        name: "SVPARAM",
        description: "Synthetic Vision parameters. Subunit is one of XFS_SV_PARAM_*",
        unit: "SYNVIS ID",
        subunit: "XFS_SV_PARAM_*",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xdc),
        name: "FDCDISEL",
        description: "Global selection of which CDI the flight director should track",
        unit: "None",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xdd),
        name: "BLOODOXY",
        description: "Blood oxygen level of given seat occupant",
        unit: "Seat position, 0=Lowest of all seats, 1=Pilot, 2=Copilot, etc",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xde),
        name: "PULSE",
        description: "Pulse rate of given seat occupant",
        unit: "Seat position, 0=Worst of all seats (too low or high), 1=Pilot, 2=Copilot, etc",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xdf),
        name: "BREATHS",
        description: "Breathing rate of given seat occupant",
        unit: "Seat position, 0=Worst of all seats (too low or high), 1=Pilot, 2=Copilot, etc",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xe0),
        name: "CARBMONOX",
        description: "Carbon Monoxide levels detected by sensor",
        unit: "Carbon Monoxide Sensor ID",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xe1),
        name: "FLOWRATE",
        description: "Oxygen flow rate",
        unit: "Seat position, 0=Worst of all seats (too low or high), 1=Pilot, 2=Copilot, etc",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xe2),
        name: "TANKPRES",
        description: "Oxygen tank pressure",
        unit: "Tank number, 0=Worst of all tanks (too low or high), 1=Tank 1, 2=Tank 2, etc",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xe3),
        name: "RNAVVS",
        description: "Vertical speed computed from RNAV",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xe4),
        name: "COMPRESET",
        description: "Selected COM Radio Preset (0=Non-preset frequency)",
        unit: "Radio",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xe5),
        name: "COMNAME",
        description: "Name of COM Radio or Preset Frequency",
        unit: "Radio",
        subunit: "0=Radio /1+=Presets",
        format: FormatId::String,
    },
    IdentInfo {
        ident: Ident(0xe6),
        name: "NAVPRESET",
        description: "Selected NAV Radio Preset (0=Non-preset frequency)",
        unit: "Radio",
        subunit: "None",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xe7),
        name: "NAVNAME",
        description: "Name of NAV Radio or Preset Frequency",
        unit: "Radio",
        subunit: "0=Radio /1+=Presets",
        format: FormatId::String,
    },
    IdentInfo {
        ident: Ident(0xe8),
        name: "VNORTH",
        description: "North component of velocity in true world coordinates",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xe9),
        name: "VEAST",
        description: "East component of velocity in true world coordinates",
        unit: "Source ID",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xea),
        name: "ENGPOWER",
        description: "Current Engine Power",
        unit: "Engine",
        subunit: "0=Shaft Power/1=Input Power Consumption/ 2+(even)= Component Shaft Power, 3+(odd)= Component Power Consumption",
        format: FormatId::Uint,
    },
    IdentInfo {
        ident: Ident(0xeb),
        name: "CHARGE",
        description: "Measured remaining battery charge",
        unit: "Battery ID/0=Sum of all",
        subunit: "None",
        format: FormatId::Sint,
    },
    IdentInfo {
        ident: Ident(0xec),
        name: "CHARGETOT",
        description: "Computed remaining charge",
        unit: "Power System ID/0=Sum of all",
        subunit: "0 = current total, 1 = total at end of flight",
        format: FormatId::Sint,
    },
];

#[cfg(test)]
mod tests {
    use super::*;

    /// The repository's own copy of the draft, so the test runs in a fresh clone.
    const SPEC: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/spec/xfsp-draft-00.txt");

    /// Removes the page headers/footers that the `.raw.txt` copy carries, so the
    /// parser works on either copy.
    fn strip_page_furniture(mut s: String) -> String {
        while let Some(a) = s.find("Spencer & Guy Expires") {
            let Some(b) = s[a..].find("July 2023") else {
                break;
            };
            s.replace_range(a..a + b + "July 2023".len(), "");
        }
        s.split_whitespace().collect::<Vec<_>>().join(" ")
    }

    /// Reading note 5: an ident is its hex groups run together (`%x00.29` is 0x29).
    fn spec_ident(token: &str) -> u32 {
        let hex: String = token.trim_start_matches("%x").split('.').collect();
        u32::from_str_radix(&hex, 16).unwrap_or_else(|e| panic!("ident {token}: {e}"))
    }

    /// (name, ident token, format name) for every entry of §3.4.
    fn spec_entries(text: &str) -> Vec<(String, String, String)> {
        let text = strip_page_furniture(text.to_owned());
        let start = text
            .find("3.4. Parameter Types This section")
            .expect("§3.4 heading");
        let end = start
            + text[start..]
                .find("4. Message Transport 4.1.")
                .expect("§4 heading");
        let sec = &text[start..end];
        let mut cursor = sec.find("attribute type.").expect("§3.4 intro") + "attribute type.".len();
        let mut out = Vec::new();
        while let Some(p) = sec[cursor..].find("Parameter ID: ") {
            let at = cursor + p;
            let pre = sec[cursor..at].trim();
            let mut words = pre.split(' ');
            let name = words.next().expect("a name").to_owned();
            assert_eq!(words.next(), Some("-"), "entry {name:?} is `NAME - text`");
            let after = &sec[at + "Parameter ID: ".len()..];
            let token = after.split(' ').next().expect("an ident").to_owned();
            let f = after.find("Format: ").expect("a format") + "Format: ".len();
            let format = after[f..]
                .split(' ')
                .next()
                .expect("format name")
                .to_owned();
            let close = f + after[f..].find(".)").expect("(See Table n.)") + 2;
            out.push((name, token, format));
            cursor = at + "Parameter ID: ".len() + close;
        }
        out
    }

    #[test]
    fn every_ident_in_the_spec_is_in_our_table() {
        let text = std::fs::read_to_string(SPEC)
            .unwrap_or_else(|e| panic!("{SPEC} is part of the repository: {e}"));
        let entries = spec_entries(&text);
        assert_eq!(entries.len(), 237, "§3.4 has 237 entries");
        assert_eq!(PARAMS.len(), entries.len(), "and so does our table");
        for (name, token, format) in &entries {
            let ident = Ident(spec_ident(token));
            assert!(ident.0 <= 0xF_FFFF, "{name} fits 20 bits");
            let f = FormatId::ALL
                .iter()
                .copied()
                .find(|f| f.spec_name() == Some(format.as_str()))
                .unwrap_or_else(|| panic!("{name}: unknown format {format}"));
            let row = lookup(ident, f)
                .unwrap_or_else(|| panic!("{name} {token} {format} missing from PARAMS"));
            assert_eq!(row.name, name, "{token} {format}");
        }
        // Our rows are unique by (ident, format), so lookup is unambiguous.
        for (i, a) in PARAMS.iter().enumerate() {
            for b in &PARAMS[i + 1..] {
                assert!(
                    (a.ident, a.format) != (b.ident, b.format),
                    "{} / {}",
                    a.name,
                    b.name
                );
            }
        }
    }

    #[test]
    fn the_typo_readings_of_note_5() {
        assert_eq!(spec_ident("%x00.29"), 0x29);
        assert_eq!(spec_ident("%x00.00.00.81"), 0x81);
        assert_eq!(by_name("MUX").map(|p| p.ident), Some(Ident(0x29)));
        assert_eq!(by_name("APPSTAT").map(|p| p.ident), Some(Ident(0x81)));
        assert_eq!(lookup(AOA, FormatId::Sint).map(|p| p.name), Some("AOA"));
        assert_eq!(lookup(AOAR, FormatId::Range).map(|p| p.name), Some("AOAR"));
        assert_eq!(lookup(AOA, FormatId::Uint), None);
    }

    #[test]
    fn the_electrical_idents_of_note_8() {
        let expect = [
            (CASMSG, "CASMSG", FormatId::CasMsg),
            (FLAPREQ, "FLAPREQ", FormatId::Sint),
            (FLAPPOS, "FLAPPOS", FormatId::Sint),
            (ECBSTAT, "ECBSTAT", FormatId::Bus),
            (PTRIMREQ, "PTRIMREQ", FormatId::Sint),
            (PTRIMPOS, "PTRIMPOS", FormatId::Sint),
            (RTRIMREQ, "RTRIMREQ", FormatId::Sint),
            (RTRIMPOS, "RTRIMPOS", FormatId::Sint),
            (BUSSTAT, "BUSSTAT", FormatId::Bus),
            (MSTRCAUTN, "MSTRCAUTN", FormatId::Bool),
            (MSTRWARN, "MSTRWARN", FormatId::Bool),
            (IAS, "IAS", FormatId::Sint),
            (GROUNDSPEED, "GROUNDSPEED", FormatId::Uint),
            (P_ALT, "P-ALT", FormatId::Sint),
            (FUELPRES, "FUELPRES", FormatId::Sint),
            (ENGRPM, "ENGRPM", FormatId::Uint),
        ];
        let raw = [
            0x05, 0x3e, 0x3f, 0x40, 0x41, 0x42, 0x43, 0x44, 0x45, 0x86, 0x87, 0x03, 0x33, 0x01,
            0x53, 0x56,
        ];
        for ((ident, n, f), r) in expect.into_iter().zip(raw) {
            assert_eq!(ident, Ident(r), "{n}");
            assert_eq!(lookup(ident, f).map(|p| p.name), Some(n));
        }
        assert_eq!(ECBSTAT.to_string(), "ECBSTAT");
        assert_eq!(
            Ident(0xd0).to_string(),
            "ident 0xd0",
            "the draft skips 0xd0"
        );
    }
}
