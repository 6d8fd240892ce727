//! The draft's dictionaries (§3.1.1, §3.2.1, §3.3): every one is an "open" enum that
//! keeps values it does not know in an `Unknown` variant, because a newer node on the
//! network may send values this draft never listed and we must pass them on intact.
//!
//! Bit-flag dictionaries (cas-msgflag, ecb-flag, fms-flag, msg-cmd-updstat-flag,
//! afcs-servo, the GS/DME/TACAN bits of fms-waypoint) are newtypes over the raw
//! integer with named constants, so unknown bits survive a round trip too.

/// Defines an open enum over an integer type with `From` both ways, the spec names,
/// and `ALL` (the named variants), so tests can cover every dictionary mechanically.
macro_rules! open_enum {
    (
        $(#[$meta:meta])*
        $vis:vis enum $name:ident : $repr:ty {
            $( $(#[$vmeta:meta])* $var:ident = $val:literal => $spec:literal, )+
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        $vis enum $name {
            $( $(#[$vmeta])* #[doc = concat!("`", $spec, "`, ", stringify!($val), " on the wire (the table named above).")] $var, )+
            /// A value this draft does not define, kept as received.
            Unknown($repr),
        }

        impl From<$repr> for $name {
            fn from(v: $repr) -> Self {
                match v {
                    $( $val => Self::$var, )+
                    other => Self::Unknown(other),
                }
            }
        }

        impl From<$name> for $repr {
            fn from(v: $name) -> $repr {
                match v {
                    $( $name::$var => $val, )+
                    $name::Unknown(other) => other,
                }
            }
        }

        impl $name {
            /// Every value the draft names, in table order.
            pub const ALL: &'static [$name] = &[$( $name::$var, )+];

            /// The name the draft gives this value, or `None` for an unknown value.
            pub fn spec_name(self) -> Option<&'static str> {
                match self {
                    $( $name::$var => Some($spec), )+
                    $name::Unknown(_) => None,
                }
            }

            /// The value on the wire.
            pub fn raw(self) -> $repr {
                self.into()
            }
        }
    };
}
pub(crate) use open_enum;

/// Defines a bit-flag newtype over the raw integer, so bits the draft does not name
/// survive a round trip; its named bits are constants in an `impl` beside it.
macro_rules! flag_set {
    ($(#[$meta:meta])* pub struct $name:ident(pub $repr:ty);) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
        pub struct $name(pub $repr);

        impl $name {
            /// Whether flag bit `bit` (one of the constants of this type) is set.
            pub fn has(self, bit: $repr) -> bool {
                self.0 & bit != 0
            }
        }
    };
}

open_enum! {
    /// Table 1, msg-class.
    pub enum MsgClass: u8 {
        Maint = 2 => "MAINT",
        Op = 3 => "OP",
        Raw = 4 => "RAW",
    }
}

open_enum! {
    /// Table 2, msg-op (the header's "message ID").
    pub enum MsgOp: u8 {
        FlightData = 2 => "FLIGHTDATA",
        DevStatus = 3 => "DEVSTATUS",
        Gdl90 = 4 => "GDL90",
    }
}

open_enum! {
    /// Table 3, msg-flag-cert: DO-178C level. Used by the header's `flags` and by the
    /// bottom three bits of each parameter's `pflags`.
    pub enum CertLevel: u8 {
        Experimental = 0 => "EXPERIMENTAL",
        LevelE = 1 => "LEVEL-E",
        LevelD = 2 => "LEVEL-D",
        LevelC = 3 => "LEVEL-C",
        LevelB = 4 => "LEVEL-B",
        LevelA = 5 => "LEVEL-A",
    }
}

open_enum! {
    /// Table 4, tcid (transcoder id).
    pub enum Tcid: u16 {
        None = 0 => "NONE",
    }
}

open_enum! {
    /// Table 5, param-confidence.
    pub enum Confidence: u8 {
        UserSel = 128 => "USERSEL",
        High = 100 => "HIGH",
        SysSel = 80 => "SYSSEL",
        Unanimous = 50 => "UNANIMOUS",
        Rational = 40 => "RATIONAL",
        Voted = 30 => "VOTED",
        Smoothed = 20 => "SMOOTHED",
        Raw = 10 => "RAW",
        Estimate = 5 => "ESTIMATE",
        Useless = 0 => "USELESS",
    }
}

open_enum! {
    /// Table 7, boolean (the BOOL format's 32-bit value; "all others undefined").
    pub enum Boolean: u32 {
        False = 0 => "FALSE",
        True = 1 => "TRUE",
    }
}

impl From<bool> for Boolean {
    fn from(b: bool) -> Self {
        if b { Boolean::True } else { Boolean::False }
    }
}

impl Boolean {
    /// `Some` only for the two defined values; the draft leaves the rest undefined.
    pub fn as_bool(self) -> Option<bool> {
        match self {
            Boolean::False => Some(false),
            Boolean::True => Some(true),
            Boolean::Unknown(_) => None,
        }
    }
}

open_enum! {
    /// Table 10 without its GS/DME/TACAN bits: the kind of navaid or fix.
    pub enum FmsWaypointKind: u8 {
        Unknown0 = 0 => "UNKNOWN",
        Vor = 1 => "VOR",
        Loc = 2 => "LOC",
        Ndb = 3 => "NDB",
        Lda = 4 => "LDA",
        Sdf = 5 => "SDF",
        Fix = 6 => "FIX",
        Ils = 7 => "ILS",
        Airport = 8 => "AIRPORT",
        DirectFrom = 9 => "DIRECTFROM",
        Weather = 10 => "WEATHER",
    }
}

flag_set! {
    /// Table 10, fms-waypoint: a kind in the low five bits plus component bits
    /// GS (0x80), DME (0x40), TACAN (0x20), which the table mixes into the same octet.
    pub struct FmsWaypoint(pub u8);
}

impl FmsWaypoint {
    /// Table 10: `GS`, a glideslope component (0x80).
    pub const GS: u8 = 0x80;
    /// Table 10: `DME`, a DME component (0x40).
    pub const DME: u8 = 0x40;
    /// Table 10: `TACAN`, a TACAN component (0x20).
    pub const TACAN: u8 = 0x20;

    /// The waypoint type of Table 10 in the low five bits.
    pub fn kind(self) -> FmsWaypointKind {
        FmsWaypointKind::from(self.0 & 0x1F)
    }
}

open_enum! {
    /// Table 11, fms-container.
    pub enum FmsContainer: u8 {
        Unknown0 = 0 => "UNKNOWN",
        None = 1 => "NONE",
        Victor = 2 => "VICTOR",
        Jet = 3 => "JET",
        Amber = 4 => "AMBER",
        Blue = 5 => "BLUE",
        Green = 6 => "GREEN",
        Red = 7 => "RED",
        Q = 8 => "Q",
        T = 9 => "T",
        Star = 10 => "STAR",
        Dp = 11 => "DP",
        App = 12 => "APP",
    }
}

open_enum! {
    /// Table 12, fms-flag, low byte: the ARINC 424 leg type.
    pub enum LegType: u8 {
        None = 0 => "NONE",
        Va = 1 => "LEGTYPE-VA",
        Vd = 2 => "LEGTYPE-VD",
        Vi = 3 => "LEGTYPE-VI",
        Vm = 4 => "LEGTYPE-VM",
        Vr = 5 => "LEGTYPE-VR",
        Ca = 6 => "LEGTYPE-CA",
        Cd = 7 => "LEGTYPE-CD",
        Ci = 8 => "LEGTYPE-CI",
        Cr = 9 => "LEGTYPE-CR",
        Cf = 10 => "LEGTYPE-CF",
        Tf = 11 => "LEGTYPE-TF",
        Df = 12 => "LEGTYPE-DF",
        Fa = 13 => "LEGTYPE-FA",
        Fc = 14 => "LEGTYPE-FC",
        Fd = 15 => "LEGTYPE-FD",
        Fm = 16 => "LEGTYPE-FM",
        Af = 17 => "LEGTYPE-AF",
        Hf = 18 => "LEGTYPE-HF",
        Ha = 19 => "LEGTYPE-HA",
        Hm = 20 => "LEGTYPE-HM",
        If = 21 => "LEGTYPE-IF",
        Pi = 22 => "LEGTYPE-PI",
        Rf = 23 => "LEGTYPE-RF",
    }
}

flag_set! {
    /// Table 12, fms-flag (16 bits): leg type in the low byte, flag bits in the high byte.
    pub struct FmsFlags(pub u16);
}

impl FmsFlags {
    /// Table 12 `FLYOVER` (%x01.00): if not present, fly by.
    pub const FLYOVER: u16 = 0x0100;
    /// Table 12 `DISC` (%x02.00): a discontinuity before the current waypoint.
    pub const DISC: u16 = 0x0200;
    /// Table 12 `ACTIVE` (%x04.00): this is the active waypoint.
    pub const ACTIVE: u16 = 0x0400;
    /// Table 12 `OBS` (%x08.00): the waypoint allows OBS to be set.
    pub const OBS: u16 = 0x0800;
    /// Table 12 `FAF` (%x10.00): the waypoint is the final approach fix or after.
    pub const FAF: u16 = 0x1000;
    /// Table 12 `SUSPEND` (%x20.00): FMS sequencing is suspended at this waypoint.
    pub const SUSPEND: u16 = 0x2000;
    /// Table 12 `LAST` (%x40.00): the last waypoint in the flight plan.
    pub const LAST: u16 = 0x4000;

    /// The Table 12 leg type (`LEGTYPE-*`) in the low byte.
    pub fn leg_type(self) -> LegType {
        LegType::from((self.0 & 0xFF) as u8)
    }
}

open_enum! {
    /// Table 15, cas-msglvl.
    pub enum CasLevel: u8 {
        Clear = 0 => "CLEAR",
        Debug = 1 => "DEBUG",
        Log = 2 => "LOG",
        Maint = 3 => "MAINT",
        Status = 4 => "STATUS",
        Advisory = 5 => "ADVISORY",
        Caution = 6 => "CAUTION",
        Warning = 7 => "WARNING",
        Comment = 10 => "COMMENT",
        UnchkItem = 11 => "UNCHKITEM",
        ChkItem = 12 => "CHKITEM",
        ChkBranch = 13 => "CHKBRANCH",
    }
}

flag_set! {
    /// Table 16, cas-msgflag (16 bits on the wire, see [`super::format::CasMsg`]).
    pub struct CasFlags(pub u16);
}

impl CasFlags {
    /// Table 16 `AUTO` (%x01): the item is automatically checked/unchecked.
    pub const AUTO: u16 = 0x01;
}

open_enum! {
    /// Table 19, ecb-state.
    pub enum EcbState: u8 {
        Unknown0 = 0 => "UNKNOWN",
        Off = 1 => "OFF",
        On = 2 => "ON",
        UnderCur = 3 => "UNDERCUR",
        Reset = 4 => "RESET",
        Forward = 5 => "FORWARD",
        Reverse = 6 => "REVERSE",
        Target = 7 => "TARGET",
        BrakeLow = 8 => "BRAKELOW",
        Shorted = 128 => "SHORTED",
        OverCur = 129 => "OVERCUR",
        OverVol = 130 => "OVERVOL",
        Disabled = 131 => "DISABLED",
        Runaway = 132 => "RUNAWAY",
        Collared = 133 => "COLLARED",
        Jammed = 134 => "JAMMED",
        Pulled = 135 => "PULLED",
        Backflow = 136 => "BACKFLOW",
    }
}

impl Default for EcbState {
    /// Table 19's UNKNOWN: nothing is known about the circuit yet.
    fn default() -> Self {
        EcbState::Unknown0
    }
}

impl EcbState {
    /// Values of 128 and up are the fault states of Table 19.
    pub fn is_fault(self) -> bool {
        self.raw() >= 128
    }
}

flag_set! {
    /// Table 20, ecb-flag.
    pub struct EcbFlags(pub u8);
}

impl EcbFlags {
    /// Table 20 `INPUTVOLTS` (%x01): the `involts` field carries a valid reading.
    pub const INPUTVOLTS: u8 = 0x01;
}

open_enum! {
    /// Table 22, param-units (16 bits: the 0x80xx values are the alternative units).
    pub enum Units: u16 {
        Unspec = 0x0000 => "UNSPEC",
        InHg = 0x0001 => "INHG",
        Ft = 0x0002 => "FT",
        Nm = 0x0003 => "NM",
        C = 0x0004 => "C",
        LbFt = 0x0005 => "LBFT",
        S = 0x0006 => "S",
        A = 0x0007 => "A",
        V = 0x0008 => "V",
        Lb = 0x0009 => "LB",
        In = 0x000a => "IN",
        Fpm = 0x000b => "FPM",
        Lbph = 0x000c => "LBPH",
        DegPs = 0x000d => "DEGPS",
        Deg = 0x000e => "DEG",
        G = 0x000f => "G",
        Rgba = 0x0010 => "RGBA",
        KHz = 0x0011 => "KHZ",
        PCent = 0x0012 => "PCENT",
        Kt = 0x0013 => "KT",
        NmPLb = 0x0014 => "NMPLB",
        KtPs = 0x0015 => "KTPS",
        Mach = 0x0016 => "MACH",
        Cpm = 0x0017 => "CPM",
        Ppm = 0x0018 => "PPM",
        Lpm = 0x0019 => "LPM",
        Kw = 0x001a => "KW",
        Ah = 0x001b => "AH",
        HPa = 0x8001 => "HPA",
        M = 0x8002 => "M",
        Sm = 0x8003 => "SM",
        F = 0x8004 => "F",
        Nwm = 0x8005 => "NWM",
        Psi = 0x8006 => "PSI",
        Mph = 0x8007 => "MPH",
        SmPLb = 0x8008 => "SMPLB",
        Min = 0x8009 => "MIN",
        Hr = 0x800a => "HR",
        Hp = 0x800b => "HP",
        Kg = 0x800c => "KG",
        Ul = 0xffff => "UL",
    }
}

open_enum! {
    /// Table 25, scb-state (software circuit breaker / application state).
    pub enum ScbState: u8 {
        Unknown0 = 0 => "UNKNOWN",
        Starting = 1 => "STARTING",
        Running = 2 => "RUNNING",
        Stopping = 3 => "STOPPING",
        Restart = 4 => "RESTART",
        Reset = 5 => "RESET",
        Hung = 6 => "HUNG",
        Degraded = 127 => "DEGRADED",
        Stopped = 128 => "STOPPED",
        StartFail = 129 => "STARTFAIL",
        Runaway = 130 => "RUNAWAY",
        OverCpu = 131 => "OVERCPU",
        OverMem = 132 => "OVERMEM",
        Exception = 133 => "EXCEPTION",
        Ended = 134 => "ENDED",
        EndError = 135 => "ENDERROR",
        Pulled = 136 => "PULLED",
        Collared = 137 => "COLLARED",
    }
}

flag_set! {
    /// Table 28, msg-cmd-updstat-flag (32 bits on the wire: UPDATE's fixed part is 56
    /// bytes only if `progflags` is a uint32).
    pub struct UpdateFlags(pub u32);
}

impl UpdateFlags {
    /// Table 28 `SUCCESS` (%x01): the update is complete and successful.
    pub const SUCCESS: u32 = 0x01;
    /// Table 28 `ERROR` (%x02): error during the update.
    pub const ERROR: u32 = 0x02;
}

/// Table 30, afcs-servo (32 bits: SERVO is 8 bytes = int32 position + this).
/// ENGAGE is the top bit; the low bit is ENGAGED (1) / DISENGAGED (0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct ServoMode(pub u32);

impl ServoMode {
    /// Table 30 `ENGAGE` (%x80.00.00.00): in a request, together with `ENGAGED`, sets the
    /// engagement.
    pub const ENGAGE: u32 = 0x8000_0000;
    /// Table 30 `ENGAGED` (%d1): in a request, keep the current engagement; in a status,
    /// engaged.
    pub const ENGAGED: u32 = 1;
    /// Table 30 `DISENGAGED` (%d0): in a request, disengage; in a status, disengaged.
    pub const DISENGAGED: u32 = 0;

    /// Whether the `ENGAGE` bit is set (Table 30).
    pub fn engage_requested(self) -> bool {
        self.0 & Self::ENGAGE != 0
    }
    /// Whether the `ENGAGED` bit is set (Table 30).
    pub fn engaged(self) -> bool {
        self.0 & Self::ENGAGED != 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Every open enum must give back exactly the raw value it was built from, known
    /// or not, and every named value must map to its named variant; no two names of
    /// one dictionary share a value, and the dictionary has as many names as its table
    /// has rows.
    macro_rules! dictionary {
        ($($test:ident: $ty:ident => $repr:ty, $rows:literal;)+) => {$(
            mod $test {
                use super::*;

                proptest! {
                    #[test]
                    fn round_trips(raw in any::<$repr>()) {
                        let v = $ty::from(raw);
                        prop_assert_eq!(<$repr>::from(v), raw);
                        let named = $ty::ALL.iter().any(|k| k.raw() == raw);
                        prop_assert_eq!(matches!(v, $ty::Unknown(_)), !named);
                        prop_assert_eq!(v.spec_name().is_some(), named);
                    }
                }

                #[test]
                fn names_are_distinct_and_complete() {
                    let mut raw: Vec<$repr> = $ty::ALL.iter().map(|k| k.raw()).collect();
                    raw.sort_unstable();
                    raw.dedup();
                    assert_eq!(raw.len(), $ty::ALL.len(), "a value named twice");
                    assert_eq!(raw.len(), $rows, "rows of the table");
                }
            }
        )+};
    }

    // Rows counted in the draft: Table 10 less its GS, DME and TACAN bits, Table 12's
    // leg types with NONE.
    dictionary! {
        msg_class: MsgClass => u8, 3;
        msg_op: MsgOp => u8, 3;
        cert_level: CertLevel => u8, 6;
        tcid: Tcid => u16, 1;
        confidence: Confidence => u8, 10;
        boolean: Boolean => u32, 2;
        fms_waypoint_kind: FmsWaypointKind => u8, 11;
        fms_container: FmsContainer => u8, 13;
        leg_type: LegType => u8, 24;
        cas_level: CasLevel => u8, 12;
        ecb_state: EcbState => u8, 18;
        units: Units => u16, 41;
        scb_state: ScbState => u8, 18;
    }

    #[test]
    fn spot_values_from_the_tables() {
        assert_eq!(Confidence::from(128), Confidence::UserSel);
        assert_eq!(Units::from(0x8001), Units::HPa);
        assert_eq!(EcbState::from(136), EcbState::Backflow);
        assert!(EcbState::Backflow.is_fault() && !EcbState::On.is_fault());
        assert_eq!(CasLevel::from(13).spec_name(), Some("CHKBRANCH"));
        assert_eq!(MsgClass::from(9), MsgClass::Unknown(9));
        let wp = FmsWaypoint(FmsWaypoint::DME | 1);
        assert_eq!(wp.kind(), FmsWaypointKind::Vor);
        assert!(wp.has(FmsWaypoint::DME) && !wp.has(FmsWaypoint::GS));
        let f = FmsFlags(FmsFlags::ACTIVE | 11);
        assert_eq!(f.leg_type(), LegType::Tf);
        assert!(f.has(FmsFlags::ACTIVE) && !f.has(FmsFlags::LAST));
        assert!(ServoMode(0x8000_0001).engage_requested());
        assert!(ServoMode(0x8000_0001).engaged());
        assert_eq!(Boolean::from(7).as_bool(), None);
    }
}
