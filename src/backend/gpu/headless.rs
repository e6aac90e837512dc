//! Quiet adapter probes on a machine without a display.
//!
//! wgpu enables every window-system extension of Vulkan (`VK_KHR_wayland_surface` among them).
//! Mesa's implicit layer `VK_LAYER_MESA_device_select` sees it and, to put the display's GPU
//! first, connects to the Wayland compositor each time the physical devices are enumerated;
//! without a runtime directory libwayland then prints "error: XDG_RUNTIME_DIR is invalid or
//! not set in the environment." to stderr, twice per probe. Where no display can be reached the
//! layer has nothing to choose by, so it is switched off (its own `NODEVICE_SELECT=1`) before
//! the first instance is made. Every adapter stays visible; only their order before
//! [`super::context`] sorts them may differ.

use std::ffi::OsString;
use std::path::Path;
use std::sync::Once;

/// Variables that ask the device-select layer for something (a device, the other GPU, or
/// the layer off already): where one is set, the layer is left as the user has it.
const LAYER_REQUESTS: &[&str] = &["NODEVICE_SELECT", "MESA_VK_DEVICE_SELECT", "DRI_PRIME"];

/// Whether the device-select layer should be switched off, given the environment `var`:
/// no Wayland display can be reached (no `WAYLAND_SOCKET`, no absolute `WAYLAND_DISPLAY`,
/// and `XDG_RUNTIME_DIR` unset or not a folder), no X display is named (`DISPLAY`), and the
/// user asked the layer for nothing.
pub fn should_quiet(var: impl Fn(&str) -> Option<OsString>) -> bool {
    if cfg!(any(not(unix), target_os = "macos", target_os = "android")) {
        return false;
    }
    let set = |name: &str| var(name).is_some_and(|v| !v.is_empty());
    let absolute_wayland = var("WAYLAND_DISPLAY").is_some_and(|v| Path::new(&v).is_absolute());
    let runtime_dir = var("XDG_RUNTIME_DIR").is_some_and(|v| Path::new(&v).is_dir());
    !set("WAYLAND_SOCKET")
        && !absolute_wayland
        && !runtime_dir
        && !set("DISPLAY")
        && !LAYER_REQUESTS.iter().any(|v| set(v))
}

/// Switch the device-select layer off where [`should_quiet`] says so, once per process. It
/// sets an environment variable, which is sound only while no other thread reads the
/// environment: a program's entry point calls it first, before it starts a thread or opens a
/// GPU (the `jkrbem` command in `main`, the Python module when it is imported), never the
/// library on a worker thread.
pub fn quiet_display_probe() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        if should_quiet(|name| std::env::var_os(name)) {
            // Only the Vulkan loader reads it, when an instance is created: after this.
            std::env::set_var("NODEVICE_SELECT", "1");
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<OsString> + 'a {
        move |name| {
            pairs
                .iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| OsString::from(v))
        }
    }

    #[test]
    #[cfg(all(unix, not(target_os = "macos")))]
    fn only_a_machine_without_any_display_loses_the_layer() {
        assert!(should_quiet(env(&[])));
        assert!(should_quiet(env(&[("XDG_RUNTIME_DIR", "/no/such/dir")])));
        assert!(should_quiet(env(&[("WAYLAND_DISPLAY", "wayland-0")])));
        let tmp = std::env::temp_dir();
        let tmp = tmp.to_str().unwrap();
        for kept in [
            [("XDG_RUNTIME_DIR", tmp)],
            [("WAYLAND_DISPLAY", "/run/user/1000/wayland-0")],
            [("WAYLAND_SOCKET", "3")],
            [("DISPLAY", ":0")],
            [("MESA_VK_DEVICE_SELECT", "10de:2330")],
            [("DRI_PRIME", "1")],
            [("NODEVICE_SELECT", "0")],
        ] {
            assert!(!should_quiet(env(&kept)), "{kept:?}");
        }
    }
}
