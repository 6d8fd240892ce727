//! The parameter table of §3.4: every ident the draft defines, with its name, what
//! the unit and subunit fields mean for it, and its format.
//!
//! Readings (icd-reading X5): MUX is written `%x00.29` and APPSTAT `%x00.00.00.81`; both are
//! read as the hex digits run together (0x29 and 0x81), which also fits their place
//! in the otherwise sequential table. AOA and AOAR are both `%x00.00.77` in the
//! draft. That is a genuine clash, so the table keeps both and a parameter is
//! identified by ident *and* format together ([`lookup`]): 0x77 with SINT is AOA,
//! 0x77 with RANGE is AOAR.
//!
//! The table was transcribed from the draft mechanically, one row per ident: the
//! `idents!` macro makes both the ident's `pub const` and its [`PARAMS`] row from
//! it. The test at the bottom re-reads the copy of the draft the repository
//! carries, `spec/xfsp-draft-00.txt` (in this crate), and checks every row against
//! it: ident, name, description, unit, subunit, format and order.

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

/// Writes each ident once: one row makes its `pub const` (documented as
/// `NAME: description`) and its entry in [`PARAMS`], in the row's order.
macro_rules! idents {
    ($($konst:ident = $id:literal, $format:ident, $name:literal, $unit:literal, $subunit:literal, $description:literal;)*) => {
        $(
            #[doc = concat!($name, ": ", $description)]
            pub const $konst: Ident = Ident($id);
        )*

        /// Every parameter of §3.4, in the draft's order.
        pub static PARAMS: &[IdentInfo] = &[$(IdentInfo {
            ident: $konst,
            name: $name,
            description: $description,
            unit: $unit,
            subunit: $subunit,
            format: FormatId::$format,
        }),*];
    };
}

// One row per §3.4 entry, in the draft's order:
// CONST = ident, format, "name", "unit usage", "subunit usage", "description";
idents! {
    GOAROUND      = 0x00, Bool,     "GOAROUND",      "None", "None", "Go around requested";
    P_ALT         = 0x01, Sint,     "P-ALT",         "Source ID", "None", "Pressure Altitude";
    T_ALT         = 0x02, Sint,     "T-ALT",         "Source ID", "None", "True Altitude";
    IAS           = 0x03, Sint,     "IAS",           "Source ID", "None", "Indicated Airspeed";
    CAS           = 0x04, Sint,     "CAS",           "Source ID", "None", "Calibrated Airspeed";
    CASMSG        = 0x05, CasMsg,   "CASMSG",        "CAS System ID", "None", "Crew Alerting System Message";
    THROTPOS      = 0x06, Sint,     "THROTPOS",      "None", "None", "Throttle position";
    INAIR         = 0x07, Bool,     "INAIR",         "None", "None", "Are we in the air (vs. on the ground)";
    BARO          = 0x08, Uint,     "BARO",          "None", "None", "Current barometric setting";
    CLTPOS        = 0x09, Sint,     "CLTPOS",        "None", "None", "Collective Position";
    CLTPOSREQ     = 0x0a, Servo,    "CLTPOSREQ",     "None", "None", "A/P Requested Collective Position";
    MAGHDG        = 0x0b, Uint,     "MAGHDG",        "Source ID", "None", "Magnetic Heading";
    MAGCRS        = 0x0c, Uint,     "MAGCRS",        "Source ID", "None", "Magnetic Course (via RNAV)";
    TRUECRS       = 0x0d, Uint,     "TRUECRS",       "Source ID", "None", "True Course (via RNAV)";
    MAGDTK        = 0x0e, Uint,     "MAGDTK",        "Source ID", "None", "Desired Course (via RNAV)";
    TRUEDTK       = 0x0f, Uint,     "TRUEDTK",       "Source ID", "None", "Desired course (via RNAV)";
    LAT           = 0x10, Sint,     "LAT",           "Source ID", "None", "Current position latitude";
    LON           = 0x11, Sint,     "LON",           "Source ID", "None", "Current position longitude";
    RNAVALT       = 0x12, Sint,     "RNAVALT",       "Source ID", "None", "Altitude measured by RNAV";
    ROLL          = 0x13, Sint,     "ROLL",          "Source ID", "None", "Current degrees of roll, -18000 being being upside down towards left, 18000 being upside down to the right";
    PITCH         = 0x14, Sint,     "PITCH",         "Source ID", "None", "Current degrees of pitch, 9000 being straight up, -9000 being straight down";
    YAW           = 0x15, Sint,     "YAW",           "Source ID", "None", "Yaw/Inclination as measured in G force";
    FUELTOT       = 0x16, Sint,     "FUELTOT",       "Fuel System ID/0=Sum of all", "0 = current total, 1 = total at end of flight", "Computed remaining fuel (divisor may be overridden by fuel type in FUELLEVLR)";
    RNAVHFOM      = 0x17, Uint,     "RNAVHFOM",      "Source ID", "None", "Horizontal Figure of Merit";
    RNAVVFOM      = 0x18, Uint,     "RNAVVFOM",      "Source ID", "None", "Vertical Figure of Merit";
    RNAVHPL       = 0x19, Uint,     "RNAVHPL",       "Source ID", "None", "Horizontal Protection Level";
    RNAVVPL       = 0x1a, Uint,     "RNAVVPL",       "Source ID", "None", "Vertical Protection Level";
    IASRT         = 0x1b, Sint,     "IASRT",         "Source ID", "None", "Indicated Airspeed Rate of Change";
    KBDSEL        = 0x1c, String,   "KBDSEL",        "Display", "None", "Activate the named on-screen keyboard or none if empty";
    KEYPRESS      = 0x1d, Uint,     "KEYPRESS",      "Display", "None", "Send the FMS encoded key press to the given display";
    SURFPOS       = 0x1e, Sint,     "SURFPOS",       "Surface Type", "Surface Type Subassembly", "Position of arbitrary control surface";
    SURFREQ       = 0x1f, Sint,     "SURFREQ",       "Surface Type", "Surface Type Subassembly", "Requested control surface position";
    SURFTORQUE    = 0x20, Sint,     "SURFTORQUE",    "Surface Type", "Surface Type Subassembly", "Aerodynamic torque applied to a control surface relative to movement";
    SURFFORCE     = 0x21, Sint,     "SURFFORCE",     "Surface Type", "Surface Type Subassembly", "Aerodynamic force applied to a control surface relative to movement";
    WINDSPD       = 0x22, Uint,     "WINDSPD",       "Source ID", "None", "Wind Speed";
    WINDBRG       = 0x23, Uint,     "WINDBRG",       "Source ID", "None", "True Bearing from which wind blows";
    COMFREQKHZ    = 0x24, Uint,     "COMFREQKHZ",    "Radio ID", "0=Radio /1+=Presets", "Communication Frequency";
    NAVFREQKHZ    = 0x25, Uint,     "NAVFREQKHZ",    "Radio ID", "0=Radio /1+=Presets", "Navigation Frequency";
    COMVOL        = 0x26, Uint,     "COMVOL",        "Radio ID", "None", "Communication Volume (0-100)";
    NAVVOL        = 0x27, Uint,     "NAVVOL",        "Radio ID", "None", "Communication Volume (0-100)";
    COMSQL        = 0x28, Uint,     "COMSQL",        "Radio ID", "None", "Communication Squelch (0-100)";
    MUX           = 0x29, Uint,     "MUX",           "MUX ID", "None", "Selected multiplexer input or output";
    ICSVOL        = 0x2a, Uint,     "ICSVOL",        "Audio Panel Unit", "0=System, 1=Pilot, 2=Copilot, rest are pax", "Intercom Volume (0-100)";
    COMSTATE      = 0x2b, Uint,     "COMSTATE",      "Radio ID", "None", "COM radio state";
    ICSRXCOMS     = 0x2c, Uint,     "ICSRXCOMS",     "Audio Panel Unit", "0=System, 1=Pilot, 2=Copilot, rest are pax", "Which COM Radios to Monitor (mask)";
    ICSRXNAVS     = 0x2d, Uint,     "ICSRXNAVS",     "Audio Panel Unit", "0=System, 1=Pilot, 2=Copilot, rest are pax", "Which NAV Radios to Monitor (mask)";
    ICSMODE       = 0x2e, Uint,     "ICSMODE",       "None", "None", "Intercom Mode";
    ICSTXCOMS     = 0x2f, Uint,     "ICSTXCOMS",     "Audio Panel Unit", "0=System, 1=Pilot, 2=Copilot, rest are pax", "Which COM Radios to Transmit (mask)";
    DATE          = 0x30, String,   "DATE",          "None", "None", "Date in YYYY-MM-DD format";
    GLOAD         = 0x31, Sint,     "GLOAD",         "Source ID", "None", "Current Normal to Aircraft Loading";
    RATEOFTURN    = 0x32, Sint,     "RATEOFTURN",    "Source ID", "None", "Turn Coordinator Rate Per Second";
    GROUNDSPEED   = 0x33, Uint,     "GROUNDSPEED",   "Source ID", "None", "Groundspeed";
    VSPEED        = 0x34, Sint,     "VSPEED",        "Source ID", "None", "Vertical speed";
    XPDRIDENT     = 0x35, Bool,     "XPDRIDENT",     "Always zero", "None", "XPDR Ident request (USERSELECT only). Non-standby transponders must IDENT regardless of UNIT. Used only to request IDENT, but IDENT state reported in XPDRMODE";
    XPDRRPS       = 0x36, Uint,     "XPDRRPS",       "XPDR ID", "None", "XPDR Replies per second (normalized)";
    XPDRSQUAWK    = 0x37, Uint,     "XPDRSQUAWK",    "XPDR ID (Rx Only) Zero for USERSELECT", "None", "XPDR Squawk as decimal integer (e.g., 1200). All transponders must change SQUAWK regardless of UNIT";
    XPDRMODE      = 0x38, Uint,     "XPDRMODE",      "XPDR ID", "None", "XPDR Mode. Note that IDENT flag is ignored in USERSELECT condition.";
    NAVOBS        = 0x39, Uint,     "NAVOBS",        "Radio/FMS ID", "None", "NAV OBS Value";
    NAVBRG        = 0x3a, Uint,     "NAVBRG",        "Radio/FMS ID", "None", "Bearing to nav aid";
    NAVCDI        = 0x3b, Sint,     "NAVCDI",        "Radio/FMS ID", "None", "Course Deviation (-1000 to 1000)";
    NAVGSI        = 0x3c, Sint,     "NAVGSI",        "Radio/FMS ID", "None", "Glide Slope (-1000 to 1000)";
    NAVFLAGS      = 0x3d, Uint,     "NAVFLAGS",      "Radio/FMS ID", "None", "Navigation Flags (see XFS_NAV_FLAG_*";
    FLAPREQ       = 0x3e, Sint,     "FLAPREQ",       "Actuator/0=Aircraft", "None", "Requested Flap Position 0 = up, 100000 = fully down, -100000 is fully negative";
    FLAPPOS       = 0x3f, Sint,     "FLAPPOS",       "Actuator/0=Aircraft", "None", "Flap actuator position, 0 = up, 100000 = fully down, -100000 is fully negative";
    ECBSTAT       = 0x40, Bus,      "ECBSTAT",       "None", "None", "ECB Status change or request, see xfs_ecb.h";
    PTRIMREQ      = 0x41, Sint,     "PTRIMREQ",      "None", "None", "Requested Pitch Trim Position (negative nose down, 0 neutral, positive nose up)";
    PTRIMPOS      = 0x42, Sint,     "PTRIMPOS",      "None", "None", "Pitch Trim Position (negative nose down, 0 neutral, positive nose up)";
    RTRIMREQ      = 0x43, Sint,     "RTRIMREQ",      "None", "None", "Requested Roll Trim Position (negative left bank, 0 neutral, positive right bank)";
    RTRIMPOS      = 0x44, Sint,     "RTRIMPOS",      "None", "None", "Roll Trim Position (negative left bank, 0 neutral, positive right bank)";
    BUSSTAT       = 0x45, Bus,      "BUSSTAT",       "None", "None", "Status of Bus";
    TEMP          = 0x46, Sint,     "TEMP",          "Location", "Sensor Number/0=Average", "Arbitrary Temperature in a location";
    TAS           = 0x47, Sint,     "TAS",           "Source ID", "None", "True Airspeed";
    TAT           = 0x48, Sint,     "TAT",           "Source ID", "None", "Total Air Temperature";
    OAT           = 0x49, Sint,     "OAT",           "Source ID", "None", "Outside Air Temperature accounting for compressibility";
    D_ALT         = 0x4a, Sint,     "D-ALT",         "Source ID", "None", "Density Altitude";
    OILPRES       = 0x4b, Sint,     "OILPRES",       "Engine", "None", "Oil Pressure";
    OILTEMP       = 0x4c, Sint,     "OILTEMP",       "Engine", "None", "Oil Temp";
    XFDFPS        = 0x4d, Uint,     "XFDFPS",        "Display", "None", "XFD Display Frames Per Second (FPS)";
    TIREPRES      = 0x4e, Sint,     "TIREPRES",      "Bogey", "Tire", "Tire Pressure";
    CHT           = 0x4f, Sint,     "CHT",           "Engine", "Cylinder/0=Max", "Cylinder Head Temperature";
    EGT           = 0x50, Sint,     "EGT",           "Engine", "Cylinder/0=Max", "Exhaust Gas Temperature";
    COOLTEMP      = 0x51, Sint,     "COOLTEMP",      "Engine", "None", "Coolant Temperature";
    FUELFLOW      = 0x52, Sint,     "FUELFLOW",      "Engine", "None", "Fuel Flow";
    FUELPRES      = 0x53, Sint,     "FUELPRES",      "Engine", "None", "Fuel Pressure";
    FUELLEVL      = 0x54, Sint,     "FUELLEVL",      "Fuel Tank ID/0=Sum of all", "None", "Fuel Level (divisor may be overridden by fuel type)";
    MANPRES       = 0x55, Sint,     "MANPRES",       "Engine", "None", "Manifold pressure";
    ENGRPM        = 0x56, Uint,     "ENGRPM",        "Engine", "None", "Engine RPM";
    PROPRPM       = 0x57, Uint,     "PROPRPM",       "Engine", "None", "Propeller RPM";
    MACH          = 0x58, Sint,     "MACH",          "Source ID", "None", "Mach";
    IASBUG        = 0x59, Sint,     "IASBUG",        "None", "None", "Target indicated airspeed";
    HDGBUG        = 0x5a, Uint,     "HDGBUG",        "None", "None", "Bugged Magnetic Heading";
    ALTBUG        = 0x5b, Sint,     "ALTBUG",        "None", "None", "Bugged Altitude";
    WAYPOINT      = 0x5c, Waypoint, "WAYPOINT",      "FMS ID", "None", "A way point in a flight plan, subunit is position in flightplan, beginning with 1 for first waypoint. Subunit 0 is only used to indicate an empty flight plan.";
    INSERT        = 0x5d, Waypoint, "INSERT",        "FMS ID", "None", "Insert A way point in a flight plan, subunit is position in flightplan which it should become (SYSSEL/USERSEL ONLY)";
    DELETE        = 0x5e, Waypoint, "DELETE",        "FMS ID", "None", "Delete A way point in a flight plan, subunit is position in flightplan starting at 1 (SYSSEL/USERSEL ONLY). Label must match";
    NOTE          = 0x5f, String,   "NOTE",          "None", "None", "Notation of something important within the quick access log or bus";
    NAVGPS        = 0x60, Uint,     "NAVGPS",        "NAV radio unit or FMS Unit Number", "None", "GPS Mode";
    NAVDIS        = 0x61, Uint,     "NAVDIS",        "FMS Unit Number", "0 = next waypoint, 1 = last waypoint", "Distance to next or last waypoint or DME for VOR/ILS/etc";
    NAVXTK        = 0x62, Sint,     "NAVXTK",        "FMS Unit Number", "None", "Cross track error (negative is left)";
    NAVETE        = 0x63, Uint,     "NAVETE",        "FMS Unit Number", "0 = next waypoint, 1 = last waypoint", "Time to next or last waypoint";
    BRIGHTNESS    = 0x64, Uint,     "BRIGHTNESS",    "None", "None", "Universal display brightness (0-1000 for night time mode, 1000-2000 for daytime modes";
    MANTEMP       = 0x65, Sint,     "MANTEMP",       "Engine", "None", "Manifold temperature";
    DIRECT        = 0x66, Waypoint, "DIRECT",        "None", "None", "Go direct to a way point in a flight plan, subunit is position in flightplan starting at 1 (SYSSEL/USERSEL ONLY). Label must match";
    ACTIVATE      = 0x67, Waypoint, "ACTIVATE",      "None", "None", "Activate leg terminating at way point in a flight plan, subunit is position in flightplan (SYSSEL/USERSEL ONLY). Label must match";
    MMPARAM       = 0x68, Sint,     "MMPARAM",       "MOVMAP ID", "XFS_MM_PARAM_*", "Moving Map parameters. Subunit is one of XFS_MM_PARAM_*";
    SERVOREQ      = 0x69, Servo,    "SERVOREQ",      "None", "None", "Requested servo position and state";
    SERVOPOS      = 0x6a, Sint,     "SERVOPOS",      "None", "None", "Current servo actuator position";
    SONICHAT      = 0x6b, Sint,     "SONICHAT",      "None", "None", "Ultrasonic rangefinder height above terrain";
    LIDARHAT      = 0x6c, Sint,     "LIDARHAT",      "Source ID", "None", "LIDAR rangefinder height above terrain";
    RADARHAT      = 0x6d, Sint,     "RADARHAT",      "Source ID", "None", "Radar rangefinder height above terrain";
    HAT           = 0x6e, Sint,     "HAT",           "Source ID", "None", "Computed height above terrain";
    COMSTANDBY    = 0x6f, Uint,     "COMSTANDBY",    "Radio ID", "None", "Standby COM Frequency (same rules and range as COMFREQKHZ)";
    NAVSTANDBY    = 0x70, Uint,     "NAVSTANDBY",    "Radio ID", "None", "Standby NAV Frequency (same rules and range as NAVFREQKHZ)";
    STALLSPEED    = 0x71, Sint,     "STALLSPEED",    "None", "None", "Estimated real-time Stall speed";
    TIMEMS        = 0x72, Uint,     "TIMEMS",        "None", "None", "Time in milliseconds from midnight zulu time";
    YTRIMREQ      = 0x73, Sint,     "YTRIMREQ",      "None", "None", "Requested Yaw Trim Position (negative left, 0 neutral, positive right)";
    YTRIMPOS      = 0x74, Sint,     "YTRIMPOS",      "None", "None", "Yaw Trim Position (negative left, 0 neutral, positive right)";
    VSPEEDBUG     = 0x75, Sint,     "VSPEEDBUG",     "None", "None", "Vertical speed bug in fpm";
    MUSICSRC      = 0x76, Uint,     "MUSICSRC",      "Audio Panel Unit", "0=System, 1=Pilot, 2=Copilot, rest are pax", "Music Source (0 = none)";
    AOA           = 0x77, Sint,     "AOA",           "Source", "None", "Angle of attack as an actual angle";
    AOAR          = 0x77, Range,    "AOAR",          "None", "None", "Angle of attack range -- should contain green (beginning of approach range), white (reference angle), yellow (approaching stall) and a red (imminent stall)";
    GPIO          = 0x78, Gpio,     "GPIO",          "I/O Module", "Module Port (0 or 1-8)", "GPIO Input/Output";
    ANALOG        = 0x79, Uint,     "ANALOG",        "I/O Module", "Module Port (1-8)", "Raw Analog value 0-4095";
    PWM           = 0x7a, Uint,     "PWM",           "I/O Module", "Module Port (1-8)", "PWM value 0-4095 -- subunit is port number, 1-8";
    XPDRACID      = 0x7b, Uint,     "XPDRACID",      "XPDR ID (Rx Only) Zero for USERSELECT", "None", "ICAO 24-bit Aircraft Identifier";
    XPDRFLID      = 0x7c, String,   "XPDRFLID",      "XPDR ID (Rx Only) Zero for USERSELECT", "None", "Up to 8-character, NULL terminated flight ID";
    THROTREQ      = 0x7d, Servo,    "THROTREQ",      "None", "None", "Requested throttle position";
    RPMREQ        = 0x7e, Uint,     "RPMREQ",        "None", "None", "Prop governor requested RPM";
    TACHTIME      = 0x7f, Uint,     "TACHTIME",      "None", "None", "Tachometer time, unit is engine";
    TOTTIME       = 0x80, Uint,     "TOTTIME",       "None", "None", "Total aircraft time";
    APPSTAT       = 0x81, App,      "APPSTAT",       "CPU ID", "Process ID", "Application Status / Requests";
    CDINAVSRC     = 0x82, Uint,     "CDINAVSRC",     "Display", "None", "Select index (> 0) of CDI NAV Source or 0 for none";
    BRGNAVSRC     = 0x83, Uint,     "BRGNAVSRC",     "Display", "None", "Select index (> 0) CDI BRG Source or 0 for none";
    COMSEL        = 0x84, Uint,     "COMSEL",        "Display", "None", "Select COM Radio for Tuning";
    NAVSEL        = 0x85, Uint,     "NAVSEL",        "Display", "None", "Select NAV Radio for Tuning";
    MSTRCAUTN     = 0x86, Bool,     "MSTRCAUTN",     "None", "None", "Master Caution Active when true. Resets by SYSSEL/ USERSEL with value of FALSE";
    MSTRWARN      = 0x87, Bool,     "MSTRWARN",      "None", "None", "Master Warning Active when true. Resets by SYSSEL/ USERSEL with value of FALSE";
    ROLLRT        = 0x88, Sint,     "ROLLRT",        "None", "None", "Rate of change of about A/C longitudinal axis (P)";
    PITCHRT       = 0x89, Sint,     "PITCHRT",       "None", "None", "Rate of change about A/C transverse axis (Q)";
    YAWRT         = 0x8a, Sint,     "YAWRT",         "None", "None", "Rate of change about A/C vertical axis (R)";
    STKPITCH      = 0x8b, Sint,     "STKPITCH",      "None", "None", "Stick Pitch Position (negative nose down, 0 neutral, positive nose up)";
    STKROLL       = 0x8c, Sint,     "STKROLL",       "None", "None", "Stick Roll Position (negative left bank, 0 neutral, positive right bank)";
    STKYAW        = 0x8d, Sint,     "STKYAW",        "None", "None", "Pedal Yaw Position (negative left, 0 neutral, positive right)";
    BATTTEMP      = 0x8e, Sint,     "BATTTEMP",      "None", "None", "Battery Temp";
    MOTORTEMP     = 0x8f, Sint,     "MOTORTEMP",     "Motor", "None", "Motor Temp";
    POWERTEMP     = 0x90, Sint,     "POWERTEMP",     "Propulsion System", "Power converter/0=Max", "Temp of a device supplying/converting power to a propulsion system";
    TORQUE        = 0x91, Sint,     "TORQUE",        "Motor/Engine", "None", "Torque";
    TAILNUM       = 0x92, String,   "TAILNUM",       "None", "None", "Up to 8-character, NULL terminated tail number";
    ROLLREQ       = 0x93, Sint,     "ROLLREQ",       "None", "None", "F/D requested degrees of roll in 100 * degrees with 0 being right side up, -18000 being being upside down towards left, 18000 being upside down to the right";
    PITCHREQ      = 0x94, Sint,     "PITCHREQ",      "None", "None", "F/D requested degrees of pitch in 100 * degrees with 0 being straight ahead, 9000 being straight up, -9000 being straight down";
    YAWREQ        = 0x95, Sint,     "YAWREQ",        "None", "None", "F/D requested G force of inclination with 0 being no yaw";
    STKPITCHREQ   = 0x96, Servo,    "STKPITCHREQ",   "None", "None", "A/P Requested Stick Pitch Position (negative nose down, 0 neutral, positive nose up)";
    STKROLLREQ    = 0x97, Servo,    "STKROLLREQ",    "None", "None", "A/P Requested Stick Roll Position (negative left bank, 0 neutral, positive right bank)";
    STKYAWREQ     = 0x98, Servo,    "STKYAWREQ",     "None", "None", "A/P Requested Pedal Yaw Position (negative left, 0 neutral, positive right)";
    FDMODEACT     = 0x99, Uint,     "FDMODEACT",     "FD Number (0 for setting values)", "None", "Active Flight Director Modes";
    FDMODEARM     = 0x9a, Uint,     "FDMODEARM",     "FD Number (0 for setting values)", "None", "Armed Flight Director Modes (XFS_AFCS_FD_MODE_*";
    ALTHOLDBUG    = 0x9b, Sint,     "ALTHOLDBUG",    "None", "None", "Altitude used by FD for altitude hold";
    APMODE        = 0x9c, Uint,     "APMODE",        "AP Number (0 for setting value)", "None", "Autopilot Modes";
    ICSSQL        = 0x9d, Uint,     "ICSSQL",        "Audio Panel Unit", "0=System, 1=Pilot, 2=Copilot, rest are pax", "Intercom Squelch (0-100)";
    PITCHBUG      = 0x9e, Sint,     "PITCHBUG",      "None", "None", "Target pitch";
    PTSPEED       = 0x9f, Sint,     "PTSPEED",       "Engine", "None", "Power Turbine Speed (commonly N1)";
    GTSPEED       = 0xa0, Sint,     "GTSPEED",       "Engine", "None", "Gas Turbine Speed (commonly N2 or Ng)";
    TIT           = 0xa1, Sint,     "TIT",           "Engine", "Turbo/0=Max", "Turbine Inlet Temperature";
    ITT           = 0xa2, Sint,     "ITT",           "Engine", "Sensor /0=Average", "Inter-Turbine Temperature";
    POWER         = 0xa3, Sint,     "POWER",         "Motor/Engine", "None", "Power under current engine and environmental conditions relative to engine design maximum";
    ENGSTATUS     = 0xa4, Uint,     "ENGSTATUS",     "Motor/Engine", "Engine Specific", "Engine specific set of flags or values";
    CABINALT      = 0xa5, Sint,     "CABINALT",      "None", "None", "Cabin Equivalent Altitude";
    CABINALTREQ   = 0xa6, Sint,     "CABINALTREQ",   "None", "None", "Cabin Equivalent Altitude";
    DIFFPRES      = 0xa7, Sint,     "DIFFPRES",      "None", "None", "Differential Pressure";
    DIFFPRESREQ   = 0xa8, Sint,     "DIFFPRESREQ",   "None", "None", "Requested Differential Pressure";
    FUELTEMP      = 0xa9, Sint,     "FUELTEMP",      "Engine/Fuel Tank", "SubLocation /0=Average, 1=Sump", "Arbitrary Temperature in a location";
    ENGSTATE      = 0xaa, Uint,     "ENGSTATE",      "Motor/Engine", "None", "Engine operating state";
    ENGSTATEREQ   = 0xab, Uint,     "ENGSTATEREQ",   "Motor/Engine", "None", "Requested Engine operating state";
    BLEEDAIR      = 0xac, Uint,     "BLEEDAIR",      "Motor/Engine", "None", "Bleed Air Level (Percent of Max)";
    BLEEDAIRREQ   = 0xad, Uint,     "BLEEDAIRREQ",   "Motor/Engine", "None", "Requested Bleed Air Level";
    LIGHTING      = 0xae, Uint,     "LIGHTING",      "System", "Specific", "Lighting Color/Level";
    LIGHTINGREQ   = 0xaf, Uint,     "LIGHTINGREQ",   "System", "Specific", "Requested Lighting Color/Level";
    ICING         = 0xb0, Uint,     "ICING",         "System/0=Aircraft", "Specific", "Deicing State";
    ICINGREQ      = 0xb1, Uint,     "ICINGREQ",      "System/0=Aircraft", "Specific", "Requested Deicing State";
    LDGGEAR       = 0xb2, Uint,     "LDGGEAR",       "Wheel/0=Aircraft", "Specific", "Landing Gear State";
    LDGGEARREQ    = 0xb3, Uint,     "LDGGEARREQ",    "Wheel/0=Aircraft", "Specific", "Landing Gear State";
    CABINTEMP     = 0xb4, Sint,     "CABINTEMP",     "Zone", "Sensor Number /0=Average", "Cabin Temperature in a zone";
    CABINTEMPREQ  = 0xb5, Sint,     "CABINTEMPREQ",  "Zone", "Sensor Number /0=Average", "Requested Cabin Temperature in a zone";
    CHKLIST       = 0xb6, CasMsg,   "CHKLIST",       "Checklist Number", "Item Number /0=Title", "Checklist Item";
    WBRANGE       = 0xb7, WbRange,  "WBRANGE",       "None", "None", "Weight and envelope per configuration";
    WBSTARM       = 0xb8, Sint,     "WBSTARM",       "Configuration", "Station /0=total /1=total no fuel", "Arm for given station";
    WBSTMAXWEIGHT = 0xb9, Sint,     "WBSTMAXWEIGHT", "Configuration", "Station /0=total /1=total no fuel", "Maximum weight at given station";
    WBSTFLAGS     = 0xba, Uint,     "WBSTFLAGS",     "Configuration", "Station /0=total /1=total no fuel", "Flags about given station";
    WBSTWEIGHT    = 0xbb, Sint,     "WBSTWEIGHT",    "Configuration", "Station /0=total /1=total no fuel", "Actual weight at given station";
    TASEFF        = 0xbc, Sint,     "TASEFF",        "None", "None", "Fuel Economy Relative to True Airspeed";
    GSEFF         = 0xbd, Sint,     "GSEFF",         "None", "None", "Fuel Economy Relative to Groundspeed";
    TIMETOEMPTY   = 0xbe, Sint,     "TIMETOEMPTY",   "Engine /0=Aircraft", "0 - smoothed, without reserve, 1 - smoothed, with reserve, 2 - without reserve, 3 - with reserve", "Time to Empty";
    DISTTOEMPTY   = 0xbf, Sint,     "DISTTOEMPTY",   "Engine /0=Aircraft", "0 - smoothed, without reserve, 1 - smoothed, with reserve, 2 - without reserve, 3 - with reserve", "Distance to Empty";
    FLIGHTSTATE   = 0xc0, Uint,     "FLIGHTSTATE",   "None", "None", "State of Flight";
    UPDATESTATE   = 0xc1, Update,   "UPDATESTATE",   "None", "None", "Status of any update";
    TORQUEREQ     = 0xc2, Sint,     "TORQUEREQ",     "Motor/Engine", "None", "Requested Torque";
    STKPITCHFRCE  = 0xc3, Sint,     "STKPITCHFRCE",  "None", "None", "Stick Pitch Force applied by the pilot, positive value - push, negative value - pull";
    STKROLLFRCE   = 0xc4, Sint,     "STKROLLFRCE",   "None", "None", "Stick Roll Force applied by the pilot, positive value - roll right, negative value - roll left";
    STKYAWFRCE    = 0xc5, Sint,     "STKYAWFRCE",    "None", "None", "Pedal Yaw Force applied by the pilot, positive value - right rudder, negative value - left rudder";
    APPITCHFRCE   = 0xc6, Sint,     "APPITCHFRCE",   "None", "None", "Auto Pilot Pitch Force exerted on control surfaces, positive value - push, negative value - pull";
    APROLLFRCE    = 0xc7, Sint,     "APROLLFRCE",    "None", "None", "Auto Pilot Roll Force exerted on control surfaces, positive value - roll right, negative value - roll left";
    APYAWFRCE     = 0xc8, Sint,     "APYAWFRCE",     "None", "None", "Auto Pilot Yaw Force exerted on control surfaces, positive value - right rudder, negative value - left rudder";
    EFBPARAM      = 0xc9, String,   "EFBPARAM",      "EFB ID", "XFS_EFB_PARAM_*", "Up to 64-character, NULL terminated parameter value";
    OILPRESCOMP   = 0xca, Sint,     "OILPRESCOMP",   "Engine", "None", "Compensated Oil Pressure";
    MACHBUG       = 0xcb, Sint,     "MACHBUG",       "None", "None", "Target Mach";
    AOART         = 0xcc, Sint,     "AOART",         "Source", "None", "Angle of attack rate of change";
    TASBUG        = 0xcd, Sint,     "TASBUG",        "None", "None", "Target true airspeed";
    GSBUG         = 0xce, Sint,     "GSBUG",         "None", "None", "Target groundspeed";
    AOABUG        = 0xcf, Sint,     "AOABUG",        "None", "None", "Bugged AOA";
    ECUTIME       = 0xd1, Uint,     "ECUTIME",       "Engine", "None", "ECU Hours";
    DBASE         = 0xd2, DBase,    "DBASE",         "CPU ID", "Process ID", "Active database information";
    EAS           = 0xd3, Sint,     "EAS",           "Source ID", "None", "Equivalent Airspeed";
    EASRT         = 0xd4, Sint,     "EASRT",         "Source ID", "None", "Equivalent Airspeed Rate of Change";
    EASBUG        = 0xd5, Sint,     "EASBUG",        "None", "None", "Target equivalent airspeed";
    POWERREQ      = 0xd6, Sint,     "POWERREQ",      "Motor/Engine", "None", "Requested power as percent of engine design maximum";
    BRAKE         = 0xd7, Uint,     "BRAKE",         "Left=1,Right=2,No direction=0", "Specific", "Wheel brake status";
    BRAKEREQ      = 0xd8, Uint,     "BRAKEREQ",      "Left=1,Right=2,No direction=0", "Specific", "Amount of brake requested";
    NAVSQL        = 0xd9, Uint,     "NAVSQL",        "Radio ID", "None", "Communication Squelch (0-100)";
    STATIONID     = 0xda, String,   "STATIONID",     "Radio ID", "None", "VOR Station ID decoded from Morse code";
    SVPARAM       = 0xdb, Sint,     "SVPARAM",       "SYNVIS ID", "XFS_SV_PARAM_*", "Synthetic Vision parameters. Subunit is one of XFS_SV_PARAM_*";
    FDCDISEL      = 0xdc, Uint,     "FDCDISEL",      "None", "None", "Global selection of which CDI the flight director should track";
    BLOODOXY      = 0xdd, Uint,     "BLOODOXY",      "Seat position, 0=Lowest of all seats, 1=Pilot, 2=Copilot, etc", "None", "Blood oxygen level of given seat occupant";
    PULSE         = 0xde, Uint,     "PULSE",         "Seat position, 0=Worst of all seats (too low or high), 1=Pilot, 2=Copilot, etc", "None", "Pulse rate of given seat occupant";
    BREATHS       = 0xdf, Uint,     "BREATHS",       "Seat position, 0=Worst of all seats (too low or high), 1=Pilot, 2=Copilot, etc", "None", "Breathing rate of given seat occupant";
    CARBMONOX     = 0xe0, Uint,     "CARBMONOX",     "Carbon Monoxide Sensor ID", "None", "Carbon Monoxide levels detected by sensor";
    FLOWRATE      = 0xe1, Uint,     "FLOWRATE",      "Seat position, 0=Worst of all seats (too low or high), 1=Pilot, 2=Copilot, etc", "None", "Oxygen flow rate";
    TANKPRES      = 0xe2, Uint,     "TANKPRES",      "Tank number, 0=Worst of all tanks (too low or high), 1=Tank 1, 2=Tank 2, etc", "None", "Oxygen tank pressure";
    RNAVVS        = 0xe3, Sint,     "RNAVVS",        "Source ID", "None", "Vertical speed computed from RNAV";
    COMPRESET     = 0xe4, Uint,     "COMPRESET",     "Radio", "None", "Selected COM Radio Preset (0=Non-preset frequency)";
    COMNAME       = 0xe5, String,   "COMNAME",       "Radio", "0=Radio /1+=Presets", "Name of COM Radio or Preset Frequency";
    NAVPRESET     = 0xe6, Uint,     "NAVPRESET",     "Radio", "None", "Selected NAV Radio Preset (0=Non-preset frequency)";
    NAVNAME       = 0xe7, String,   "NAVNAME",       "Radio", "0=Radio /1+=Presets", "Name of NAV Radio or Preset Frequency";
    VNORTH        = 0xe8, Sint,     "VNORTH",        "Source ID", "None", "North component of velocity in true world coordinates";
    VEAST         = 0xe9, Sint,     "VEAST",         "Source ID", "None", "East component of velocity in true world coordinates";
    ENGPOWER      = 0xea, Uint,     "ENGPOWER",      "Engine", "0=Shaft Power/1=Input Power Consumption/ 2+(even)= Component Shaft Power, 3+(odd)= Component Power Consumption", "Current Engine Power";
    CHARGE        = 0xeb, Sint,     "CHARGE",        "Battery ID/0=Sum of all", "None", "Measured remaining battery charge";
    CHARGETOT     = 0xec, Sint,     "CHARGETOT",     "Power System ID/0=Sum of all", "0 = current total, 1 = total at end of flight", "Computed remaining charge";
}

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

    /// icd-reading X5: an ident is its hex groups run together (`%x00.29` is 0x29).
    fn spec_ident(token: &str) -> u32 {
        let hex: String = token.trim_start_matches("%x").split('.').collect();
        u32::from_str_radix(&hex, 16).unwrap_or_else(|e| panic!("ident {token}: {e}"))
    }

    /// One entry of §3.4 as the draft writes it:
    /// `NAME - description Parameter ID: %x.. Unit Usage: .. SubUnit Usage: .. Format: F (See Table n.)`.
    struct SpecEntry {
        name: String,
        description: String,
        token: String,
        unit: String,
        subunit: String,
        format: String,
    }

    /// The text of `s` between `open` and the next `close`, and what follows `close`.
    fn between<'a>(s: &'a str, open: &str, close: &str) -> (&'a str, &'a str) {
        let a = s
            .find(open)
            .unwrap_or_else(|| panic!("{open:?} in {s:.80}"))
            + open.len();
        let b = a + s[a..]
            .find(close)
            .unwrap_or_else(|| panic!("{close:?} in {s:.80}"));
        (&s[a..b], &s[b + close.len()..])
    }

    /// Every entry of §3.4, in the draft's order.
    fn spec_entries(text: &str) -> Vec<SpecEntry> {
        let text = strip_page_furniture(text.to_owned());
        let start = text
            .find("3.4. Parameter Types This section")
            .expect("§3.4 heading");
        let end = start
            + text[start..]
                .find("4. Message Transport 4.1.")
                .expect("§4 heading");
        let sec = &text[start..end];
        let mut rest =
            &sec[sec.find("attribute type.").expect("§3.4 intro") + "attribute type.".len()..];
        let mut out = Vec::new();
        while rest.contains("Parameter ID: ") {
            let (pre, after) = between(rest, "", " Parameter ID: ");
            let (name, description) = pre
                .trim()
                .split_once(" - ")
                .unwrap_or_else(|| panic!("entry {pre:?} is `NAME - text`"));
            let (token, after) = between(after, "", " Unit Usage: ");
            let (unit, after) = between(after, "", " SubUnit Usage: ");
            let (subunit, after) = between(after, "", " Format: ");
            let (format, after) = between(after, "", " (See Table ");
            let (_, after) = between(after, "", ".)");
            out.push(SpecEntry {
                name: name.to_owned(),
                description: description.to_owned(),
                token: token.to_owned(),
                unit: unit.to_owned(),
                subunit: subunit.to_owned(),
                format: format.to_owned(),
            });
            rest = after;
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
        for e in &entries {
            let (name, token) = (&e.name, &e.token);
            let ident = Ident(spec_ident(token));
            assert!(ident.0 <= 0xF_FFFF, "{name} fits 20 bits");
            let f = FormatId::ALL
                .iter()
                .copied()
                .find(|f| f.spec_name() == Some(e.format.as_str()))
                .unwrap_or_else(|| panic!("{name}: unknown format {}", e.format));
            let row = lookup(ident, f)
                .unwrap_or_else(|| panic!("{name} {token} {} missing from PARAMS", e.format));
            assert_eq!(row.name, name, "{token} {}", e.format);
            assert_eq!(row.description, e.description, "{name}: description");
            assert_eq!(row.unit, e.unit, "{name}: Unit Usage");
            assert_eq!(row.subunit, e.subunit, "{name}: SubUnit Usage");
        }
        // The table is in the draft's order, so a reader can check it row by row.
        let ours: Vec<_> = PARAMS.iter().map(|p| p.name).collect();
        let theirs: Vec<_> = entries.iter().map(|e| e.name.as_str()).collect();
        assert_eq!(ours, theirs);
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
    fn typo_idents_read_as_their_hex_and_aoa_is_told_from_aoar_by_format() {
        assert_eq!(spec_ident("%x00.29"), 0x29);
        assert_eq!(spec_ident("%x00.00.00.81"), 0x81);
        assert_eq!(by_name("MUX").map(|p| p.ident), Some(Ident(0x29)));
        assert_eq!(by_name("APPSTAT").map(|p| p.ident), Some(Ident(0x81)));
        assert_eq!(lookup(AOA, FormatId::Sint).map(|p| p.name), Some("AOA"));
        assert_eq!(lookup(AOAR, FormatId::Range).map(|p| p.name), Some("AOAR"));
        assert_eq!(lookup(AOA, FormatId::Uint), None);
    }

    #[test]
    fn the_electrical_idents_have_their_names_and_formats() {
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
