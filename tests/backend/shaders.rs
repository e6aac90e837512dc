//! Every WGSL module of the GPU backend parses and validates with naga (the compiler wgpu
//! uses), without any GPU adapter; and every kernel's explicit bind group layout
//! (`jkrbem::backend::gpu::shaders`) lists exactly the group-0 bindings its entry point uses,
//! with the access (uniform, read-only storage, read-write storage) the shader declares.

use jkrbem::backend::gpu::recorder::Binding;
use jkrbem::backend::gpu::shaders::MODULES;
use naga::valid::{Capabilities, GlobalUse, ValidationFlags, Validator};
use naga::{AddressSpace, StorageAccess};

#[test]
fn every_module_validates_and_every_layout_matches_what_its_kernel_uses() {
    for (name, source, kernels) in MODULES {
        let module = naga::front::wgsl::parse_str(source)
            .unwrap_or_else(|e| panic!("{name} does not parse:\n{}", e.emit_to_string(source)));
        let info = Validator::new(ValidationFlags::all(), Capabilities::default())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name} does not validate:\n{}", e.emit_to_string(source)));
        assert_eq!(
            module.entry_points.len(),
            kernels.len(),
            "{name}: every entry point has a layout and every layout an entry point"
        );
        for (i, ep) in module.entry_points.iter().enumerate() {
            let layout = kernels
                .iter()
                .find(|k| k.entry == ep.name)
                .unwrap_or_else(|| panic!("{name}: no layout for {}", ep.name));
            let uses = info.get_entry_point(i);
            let mut used: Vec<(u32, Binding)> = module
                .global_variables
                .iter()
                .filter(|(h, _)| !uses[*h].is_empty())
                .filter_map(|(_, g)| {
                    let b = g.binding.as_ref()?;
                    assert_eq!(b.group, 0, "{name}: only group 0 is used");
                    let kind = match g.space {
                        AddressSpace::Uniform => Binding::Uniform,
                        AddressSpace::Storage { access }
                            if access.contains(StorageAccess::STORE) =>
                        {
                            Binding::ReadWrite
                        }
                        AddressSpace::Storage { .. } => Binding::Read,
                        other => panic!("{name}: binding {} in {other:?}", b.binding),
                    };
                    Some((b.binding, kind))
                })
                .collect();
            used.sort_by_key(|&(b, _)| b);
            assert_eq!(
                used, layout.bindings,
                "{name}: {} uses these bindings, its layout lists others",
                ep.name
            );
            // A read-write binding the kernel only reads would still be right, but it would
            // keep wgpu from overlapping it with other readers: say so if it happens.
            for (h, g) in module.global_variables.iter() {
                if let (Some(b), AddressSpace::Storage { access }) = (&g.binding, g.space) {
                    if access.contains(StorageAccess::STORE) && uses[h] == GlobalUse::READ {
                        println!(
                            "note: {name}: {} only reads read-write binding {}",
                            ep.name, b.binding
                        );
                    }
                }
            }
        }
        println!(
            "{name}: {} kernels validate and match their layouts",
            kernels.len()
        );
    }
}
