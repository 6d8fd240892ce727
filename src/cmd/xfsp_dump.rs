//! `vpx-efis xfsp-dump`: decoded XFSp traffic, one parameter per line.
//!
//! Text: `src 0x5650 #12 ECBSTAT unit 5/0 BUS ON draw 2.5 A max 5.0 A "AVIONICS" HIGH
//! expire 2.7s EXPERIMENTAL`. `--json`: one object per parameter with the same fields.
//! Malformed datagrams, duplicates and out-of-order messages get a line of their own
//! (ordering is judged per source as §4.4 says, so the dump shows what a receiver
//! would process). A `--xfsp` that is not a multicast group is a unicast address to
//! listen on.

use std::io::Write;
use std::net::{Ipv4Addr, SocketAddr};

use anyhow::Context;
use clap::Args;
use serde_json::{Value as Json, json};

use crate::settings::values;
use crate::xfsp::format::{Bus, CasMsg, Value, latin1};
use crate::xfsp::net::{Target, XfspNet};
use crate::xfsp::{Expire, Header, ParamView, Received, Receiver, idents};

/// The scales behind the numbers, for `xfsp-dump --help` (the draft names none; the
/// the guide's XFSp chapter says the same).
pub const SCALES_HELP: &str = "\
Numbers as vpx-efis publishes them (the XFSp draft names no scales; this dump prints
BUS values already divided, in A and V):
  ECBSTAT    unit = VP-X device id 0-30, label \"VP-X/\" and the circuit's name
             (System/Item); drawamps and maxamps in tenths of an ampere (25 = 2.5 A);
             the volts fields are 0 (the VP-X measures no voltage per pin, so
             INPUTVOLTS is not set)
  BUSSTAT    unit 0 \"VP-X/MAIN BUS\": outvolts in tenths of a volt (138 = 13.8 V),
             drawamps = the unit's total current in tenths of an ampere; unit 1
             \"VP-X/AUX BATTERY\": outvolts in tenths of a volt, drawamps 0
  CASMSG     unit = our CAS system id (our XFSp source id), label \"NAME: FAULT\"
  FLAPPOS    0 = flaps up endpoint, 100000 = down endpoint
  PTRIMPOS   -100000 = nose-down endpoint, 0 = neutral, 100000 = nose-up endpoint
  RTRIMPOS   -100000 = left endpoint, 0 = neutral, 100000 = right endpoint
  MSTRCAUTN, MSTRWARN  unit 0, TRUE while an unreset CAUTION / WARNING stands
Requests use the same scales (FLAPREQ, PTRIMREQ, RTRIMREQ on +-100000).

Air data the gateway forwards to the VP-X (EXTERNAL_DATA) must arrive as whole
numbers (SINT or UINT), in the units the VP-X expects; nothing is converted:
  IAS, GROUNDSPEED  the EFIS's speed unit, the one the VP-X's flap and trim speed
                    limits are set in (knots in vpx-efis's setup screens)
  P-ALT             feet
  FUELPRES          pounds per square inch
  ENGRPM            revolutions per minute";

#[derive(Debug, Args)]
#[command(after_help = SCALES_HELP)]
pub struct XfspDumpArgs {
    /// Multicast GROUP:PORT to listen on.
    #[arg(long, default_value = "224.0.2.69:20234", value_name = "GROUP:PORT", value_parser = values::xfsp_target)]
    pub xfsp: String,
    /// Local interface address to join the group on.
    #[arg(long, default_value = "0.0.0.0", value_name = "ADDR", value_parser = values::iface)]
    pub xfsp_iface: Ipv4Addr,
    /// JSON lines instead of text.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: XfspDumpArgs) -> anyhow::Result<()> {
    let target = Target::parse(&args.xfsp).map_err(anyhow::Error::msg)?;
    let iface = args.xfsp_iface;
    let net = XfspNet::listen(&target, iface)
        .with_context(|| format!("cannot listen on XFSp {target}"))?;
    eprintln!("vpx-efis xfsp-dump: listening on {target}");
    let mut receiver = Receiver::default();
    let stdout = std::io::stdout();
    for d in net.incoming() {
        let mut out = stdout.lock();
        for line in dump(&mut receiver, d.from, &d.bytes, d.at, args.json) {
            if writeln!(out, "{line}").is_err() {
                // Standard output closed (e.g. piped into `head`): done.
                return Ok(());
            }
        }
        let _ = out.flush();
    }
    Ok(())
}

/// The lines for one datagram.
pub fn dump(
    receiver: &mut Receiver,
    from: SocketAddr,
    bytes: &[u8],
    at: std::time::Instant,
    json: bool,
) -> Vec<String> {
    let verdict = |what: &str, h: Option<&Header>, detail: String| {
        if json {
            json!({
                "from": from.to_string(),
                "event": what,
                "src": h.map(|h| h.src_id),
                "num": h.map(|h| h.msg_num),
                "len": bytes.len(),
                "detail": detail,
            })
            .to_string()
        } else {
            let who = h.map_or_else(String::new, |h| {
                format!(" src {:#06x} #{}", h.src_id, h.msg_num)
            });
            format!(
                "{what} datagram from {from}{who} ({} bytes){detail}",
                bytes.len()
            )
        }
    };
    match receiver.receive(bytes, at) {
        Received::Malformed(e) => vec![verdict("malformed", None, format!(": {e}"))],
        Received::Duplicate(h) => vec![verdict("duplicate", Some(&h), String::new())],
        Received::OutOfOrder(h) => vec![verdict("out-of-order", Some(&h), String::new())],
        Received::Fresh(view) => {
            let h = *view.header();
            if !view.has_params() {
                return vec![verdict(
                    "raw",
                    Some(&h),
                    format!(
                        ": class {}, op {}",
                        u8::from(h.class),
                        h.op.spec_name().unwrap_or("?")
                    ),
                )];
            }
            view.params().map(|p| param_line(&h, &p, json)).collect()
        }
    }
}

fn expire_text(e: Expire) -> String {
    match e.millis() {
        None => "never".into(),
        Some(ms) if ms < 1000 => format!("{ms}ms"),
        Some(ms) => format!("{}s", ms as f64 / 1000.0),
    }
}

fn param_line(h: &Header, p: &ParamView<'_>, json: bool) -> String {
    let ph = &p.header;
    let name = idents::lookup(ph.ident, ph.format)
        .or_else(|| idents::lookup_ident(ph.ident))
        .map_or_else(|| format!("{:#x}", ph.ident.0), |i| i.name.to_string());
    let confidence = named(ph.confidence.spec_name(), u8::from(ph.confidence));
    let cert = named(ph.cert().spec_name(), u8::from(ph.cert()));
    let format = ph
        .format
        .spec_name()
        .map_or_else(|| format!("format {}", u8::from(ph.format)), str::to_string);
    let value = p.value();
    if json {
        json!({
            "src": h.src_id,
            "num": h.msg_num,
            "ident": name,
            "ident_id": ph.ident.0,
            "unit": ph.unit,
            "subunit": ph.subunit,
            "format": format,
            "value": match &value {
                Ok(v) => value_json(v),
                Err(e) => json!({ "error": e.to_string() }),
            },
            "confidence": confidence,
            "expire_ms": ph.expire.millis(),
            "cert": cert,
        })
        .to_string()
    } else {
        let v = match &value {
            Ok(v) => value_text(v),
            Err(e) => format!("undecodable ({e})"),
        };
        format!(
            "src {:#06x} #{} {name} unit {}/{} {format} {v} {confidence} expire {} {cert}",
            h.src_id,
            h.msg_num,
            ph.unit,
            ph.subunit,
            expire_text(ph.expire)
        )
    }
}

/// A value's name in the draft, or its number where the draft names none.
fn named(name: Option<&str>, raw: impl std::fmt::Display) -> String {
    name.map_or_else(|| raw.to_string(), str::to_string)
}

fn bus_text(b: &Bus) -> String {
    format!(
        "{} draw {:.1} A max {:.1} A out {:.1} V{} {:?}",
        named(b.state.spec_name(), u8::from(b.state)),
        b.draw_amps_a(),
        Bus::from_tenths(b.max_amps),
        b.out_volts_v(),
        if b.flags.has(crate::xfsp::EcbFlags::INPUTVOLTS) {
            format!(" in {:.1} V", Bus::from_tenths(b.in_volts))
        } else {
            String::new()
        },
        latin1(&b.label)
    )
}

fn cas_text(c: &CasMsg) -> String {
    format!(
        "{} {:?}",
        named(c.level.spec_name(), u8::from(c.level)),
        latin1(&c.label)
    )
}

fn value_text(v: &Value) -> String {
    match v {
        Value::Bool(b) => b
            .spec_name()
            .map_or_else(|| format!("BOOL {}", u32::from(*b)), str::to_string),
        Value::Uint(n) => n.to_string(),
        Value::Sint(n) => n.to_string(),
        Value::String(s) => format!("{:?}", latin1(s)),
        Value::Bus(b) => bus_text(b),
        Value::CasMsg(c) => cas_text(c),
        other => format!("{other:?}"),
    }
}

fn value_json(v: &Value) -> Json {
    match v {
        Value::Bool(b) => b.as_bool().map_or(json!(u32::from(*b)), Json::Bool),
        Value::Uint(n) => json!(n),
        Value::Sint(n) => json!(n),
        Value::String(s) => json!(latin1(s)),
        Value::Bus(b) => json!({
            "state": b.state.spec_name().map_or_else(|| json!(u8::from(b.state)), |s| json!(s)),
            "flags": b.flags.0,
            "in_volts": Bus::from_tenths(b.in_volts),
            "draw_amps": b.draw_amps_a(),
            "max_amps": Bus::from_tenths(b.max_amps),
            "out_volts": b.out_volts_v(),
            "label": latin1(&b.label),
        }),
        Value::CasMsg(c) => json!({
            "level": c.level.spec_name().map_or_else(|| json!(u8::from(c.level)), |s| json!(s)),
            "flags": c.flags.0,
            "label": latin1(&c.label),
        }),
        other => json!({ "debug": format!("{other:?}") }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn help_states_the_scale_of_every_published_number_and_the_air_data_units() {
        let help = XfspDumpArgs::augment_args(clap::Command::new("xfsp-dump"))
            .render_long_help()
            .to_string();
        for words in [
            "tenths of an ampere",
            "tenths of a volt",
            "100000 = down endpoint",
            "-100000 = nose-down",
            "-100000 = left",
            "P-ALT             feet",
            "pounds per square inch",
            "knots",
        ] {
            assert!(help.contains(words), "{words:?} missing from:\n{help}");
        }
    }
    use crate::xfsp::{CertLevel, MsgKind, Parameter, Sender};

    fn from() -> SocketAddr {
        "127.0.0.1:1".parse().unwrap()
    }

    #[test]
    fn one_line_per_parameter_then_duplicates_and_damage_say_so() {
        let mut s = Sender::new(0x1234, 7);
        let d = s
            .pack(
                MsgKind::flight_data(CertLevel::LevelC),
                &[
                    Parameter::new(idents::IAS, Value::Sint(95)).unit(2),
                    Parameter::new(idents::ECBSTAT, Value::Bus(Bus::default())).unit(5),
                ],
            )
            .unwrap();
        let mut r = Receiver::default();
        let lines = dump(&mut r, from(), &d[0], std::time::Instant::now(), false);
        assert_eq!(lines.len(), 2);
        assert!(
            lines[0].starts_with("src 0x1234 #7 IAS unit 2/0 SINT 95 HIGH expire never"),
            "{}",
            lines[0]
        );
        assert!(
            lines[1].contains("ECBSTAT unit 5/0 BUS UNKNOWN"),
            "{}",
            lines[1]
        );
        assert!(
            dump(&mut r, from(), &d[0], std::time::Instant::now(), false)[0]
                .starts_with("duplicate")
        );
        let j: Json = serde_json::from_str(
            &dump(&mut r, from(), &d[0][..5], std::time::Instant::now(), true)[0],
        )
        .unwrap();
        assert_eq!(j["event"], "malformed");
        let mut s2 = Sender::new(0x1234, 8);
        let d2 = s2
            .pack(
                MsgKind::flight_data(CertLevel::LevelC),
                &[Parameter::new(idents::IAS, Value::Sint(96)).unit(2)],
            )
            .unwrap();
        let j: Json =
            serde_json::from_str(&dump(&mut r, from(), &d2[0], std::time::Instant::now(), true)[0])
                .unwrap();
        assert_eq!(
            (j["ident"].as_str(), j["value"].as_i64()),
            (Some("IAS"), Some(96))
        );
        assert_eq!(j["expire_ms"], Json::Null);
    }
}
