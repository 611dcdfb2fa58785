//! `plan.html`: the plan in the browser, offline. One self-contained file: Leaflet 1.9.4
//! (vendored in `assets/leaflet/`, BSD-2-Clause) and the plan are inlined, the terrain
//! hillshade is an embedded PNG overlay, and the map is drawn in plan metres (Leaflet's
//! `CRS.Simple`), so no tile server, network or projection library is needed. One layer per
//! sortie (swaths, transfers, returns), one for the fields; a click on any feature shows its
//! figures.

use serde_json::Value;

const LEAFLET_JS: &str = include_str!("../../assets/leaflet/leaflet.js");
const LEAFLET_CSS: &str = include_str!("../../assets/leaflet/leaflet.css");

/// The terrain picture under the plan: a PNG and the plan-metre box it covers.
pub struct Overlay<'a> {
    /// The picture, PNG bytes.
    pub png: &'a [u8],
    /// West edge of the box, plan metres.
    pub min_x: f64,
    /// South edge of the box, plan metres.
    pub min_y: f64,
    /// East edge of the box, plan metres.
    pub max_x: f64,
    /// North edge of the box, plan metres.
    pub max_y: f64,
}

pub(crate) fn base64(bytes: &[u8]) -> String {
    const TABLE: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut text = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let n = (u32::from(chunk[0]) << 16)
            | (u32::from(*chunk.get(1).unwrap_or(&0)) << 8)
            | u32::from(*chunk.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= chunk.len() {
                text.push(TABLE[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                text.push('=');
            }
        }
    }
    text
}

/// Text safe inside a `<script>` element.
fn script_safe(json: &str) -> String {
    json.replace("</", "<\\/")
}

/// The page. `plan_metres` is the plan's GeoJSON in plan metres (`"crs": "local"`).
pub fn plan_html(title: &str, plan_metres: &Value, overlay: Option<&Overlay>) -> String {
    let overlay_json = match overlay {
        Some(o) => format!(
            r#"{{"url": "data:image/png;base64,{}", "bounds": [[{}, {}], [{}, {}]]}}"#,
            base64(o.png),
            o.min_y,
            o.min_x,
            o.max_y,
            o.max_x
        ),
        None => "null".into(),
    };
    let title_json = serde_json::to_string(title).expect("a string");
    let plan_json = serde_json::to_string(plan_metres).expect("JSON value");
    format!(
        r##"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title_html}</title>
<style>
{LEAFLET_CSS}
html, body, #map {{ height: 100%; margin: 0; background: #f4f4f0; font-family: sans-serif; }}
.agripath-title {{ background: rgba(255,255,255,0.9); padding: 6px 10px; border-radius: 4px; font-size: 14px; }}
.agripath-popup td {{ padding: 1px 6px; font-size: 12px; }}
.agripath-popup td:first-child {{ color: #555; }}
.agripath-rank {{ background: none; border: none; box-shadow: none; font: bold 11px Helvetica, Arial, sans-serif; padding: 0; }}
</style>
<script>
{LEAFLET_JS}
</script>
</head>
<body>
<div id="map"></div>
<script>
const TITLE = {title_json};
const PLAN = {plan_json};
const OVERLAY = {overlay_json};
const COLOURS = ["#0072B2", "#E69F00", "#009E73", "#CC79A7", "#D55E00", "#56B4E9", "#000000", "#999933"];
const map = L.map("map", {{ crs: L.CRS.Simple, minZoom: -8, maxZoom: 6, zoomSnap: 0.25 }});
if (OVERLAY) {{ L.imageOverlay(OVERLAY.url, OVERLAY.bounds, {{ opacity: 0.75 }}).addTo(map); }}
function style(feature) {{
  const p = feature.properties;
  const colour = COLOURS[(p.sortie || 0) % COLOURS.length];
  switch (p.kind) {{
    case "field": return {{ color: "#2e7d32", weight: 2, fillColor: "#66bb6a", fillOpacity: 0.15 }};
    case "obstacle": return {{ color: "#c62828", weight: 2, fillColor: "#ef5350", fillOpacity: 0.45 }};
    case "swath": case "edge": return {{ color: colour, weight: 2.5, opacity: 0.9 }};
    case "transfer": return {{ color: p.climbs ? "#d62728" : "#777", weight: 1.2, dashArray: "4 3" }};
    case "return": return {{ color: "#ff6f00", weight: 1.5, dashArray: "6 4" }};
    default: return {{ color: "#333", weight: 1 }};
  }}
}}
// The popup is built as nodes with text, never as HTML from the properties: a field's name
// comes from the operator's file and must not run as markup (trial 7).
function popup(feature) {{
  const table = document.createElement("table");
  table.className = "agripath-popup";
  for (const [key, value] of Object.entries(feature.properties)) {{
    const row = table.insertRow();
    row.insertCell().textContent = key;
    row.insertCell().textContent = typeof value === "number" ? String(Math.round(value * 1000) / 1000)
      : (value !== null && typeof value === "object") ? JSON.stringify(value) : String(value);
  }}
  return table;
}}
const groups = new Map();
function group(name) {{
  if (!groups.has(name)) {{ groups.set(name, L.featureGroup().addTo(map)); }}
  return groups.get(name);
}}
for (const feature of PLAN.features) {{
  const p = feature.properties;
  const name = (p.kind === "field" || p.kind === "obstacle") ? "fields"
    : p.kind === "supply" ? "supply point"
    : p.kind === "supply_option" ? "other supply places"
    : "sortie " + ((p.sortie || 0) + 1);
  L.geoJSON(feature, {{
    style: style,
    pointToLayer: (f, latlng) => f.properties.kind === "supply_option"
      ? L.circleMarker(latlng, {{ radius: 6, color: "#222", weight: 1.5, dashArray: "3 2",
          fillColor: "#ffeb3b", fillOpacity: 0.35 }})
          .bindTooltip("option " + f.properties.rank, {{ permanent: true, direction: "top", className: "agripath-rank" }})
      : L.circleMarker(latlng, {{
      radius: f.properties.kind === "supply" ? 8 : 5,
      color: f.properties.kind === "supply" ? "#000" : "#ff6f00",
      fillColor: f.properties.kind === "supply" ? "#ffeb3b" : "#ff6f00",
      fillOpacity: 0.9, weight: 2 }}),
    onEachFeature: (f, layer) => layer.bindPopup(popup(f)),
  }}).addTo(group(name));
}}
const names = [...groups.keys()].sort((a, b) => a.localeCompare(b, undefined, {{ numeric: true }}));
const overlays = {{}};
for (const name of names) {{ overlays[name] = groups.get(name); }}
L.control.layers(null, overlays, {{ collapsed: false }}).addTo(map);
L.control.scale({{ imperial: false }}).addTo(map);
const everything = L.featureGroup([...groups.values()]);
map.fitBounds(everything.getBounds().pad(0.05));
const banner = L.control({{ position: "bottomleft" }});
banner.onAdd = () => {{ const d = L.DomUtil.create("div", "agripath-title"); d.textContent = TITLE + " · "; const sheet = L.DomUtil.create("a", "", d); sheet.href = "sheet.html"; sheet.textContent = "mission sheet"; return d; }};
banner.addTo(map);
document.body.dataset.features = String(PLAN.features.length);
</script>
</body>
</html>
"##,
        title_html = title.replace('&', "&amp;").replace('<', "&lt;"),
        plan_json = script_safe(&plan_json),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_the_standard_alphabet() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }

    #[test]
    fn the_page_inlines_leaflet_and_the_plan() {
        let plan = serde_json::json!({"type": "FeatureCollection", "features": [
            {"type": "Feature", "properties": {"kind": "field", "name": "a</script>"}, "geometry": {"type": "Point", "coordinates": [0, 0]}}
        ]});
        let page = plan_html("t", &plan, None);
        assert!(page.contains("Leaflet") && page.contains("L.CRS.Simple"));
        assert!(
            !page.contains("a</script>"),
            "a closing tag inside the data would end the script"
        );
        assert!(!page.contains("http://") || !page.contains("<script src"));
    }
}
