//! Every shader parses and validates with naga: no GPU needed.

use carom_render::shaders::ALL;

#[test]
fn every_shader_is_valid_wgsl() {
    for (name, source) in ALL {
        let module = naga::front::wgsl::parse_str(source)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        for entry in ["vs", "fs"] {
            assert!(
                module.entry_points.iter().any(|p| p.name == entry),
                "{name} has no `{entry}`"
            );
        }
    }
}
