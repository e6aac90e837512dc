#!/usr/bin/env python3
"""cuFFT reference for `jkrbem bench` on an NVIDIA GPU (needs CuPy).

Times, on the same device and in the same run, what one jkrbem convolution does with cuFFT:
the zero-padded real 2-D FFT convolution of an N x N f32 field (rfft2 of 2N x 2N, multiply by a
real spectrum, irfft2, crop), the bare forward + inverse R2C/C2R pair on 2N x 2N (the floor the
issue sets the convolution against), the same pair with VkFFT when pyvkfft imports, and the
device's copy bandwidth, so the time per CG iteration reported by `jkrbem bench --backends gpu`
can be set against all of them.

    python3 benches/cufft_floor.py --grids 256,512,1024,2048 --repeats 50 --out jkrbem-out/bench/cufft.csv
"""
import argparse
import csv
import sys

try:
    import cupy as cp
except ImportError:  # pragma: no cover
    sys.exit("cupy is not installed: this script needs an NVIDIA GPU with CuPy")


def timed(fn, repeats):
    """Median time of fn() in milliseconds, measured with CUDA events after a warm-up."""
    fn()
    cp.cuda.Device().synchronize()
    times = []
    for _ in range(repeats):
        start, stop = cp.cuda.Event(), cp.cuda.Event()
        start.record()
        fn()
        stop.record()
        stop.synchronize()
        times.append(cp.cuda.get_elapsed_time(start, stop))
    times.sort()
    return times[len(times) // 2]


VKFFT_NOTE = []


def vkfft_pair(real, repeats):
    """Median ms of VkFFT's forward R2C plus inverse C2R of `real` (out of place), or None."""
    try:
        from pyvkfft.cuda import VkFFTApp
    except Exception as e:  # pragma: no cover - depends on the machine
        if not VKFFT_NOTE:
            VKFFT_NOTE.append(str(e))
            print(f"pyvkfft: not available ({e})")
        return None
    try:
        app = VkFFTApp(real.shape, real.dtype, ndim=2, inplace=False, r2c=True)
        spec = cp.empty((real.shape[0], real.shape[1] // 2 + 1), dtype=cp.complex64)
        back = cp.empty_like(real)
        return timed(lambda: (app.fft(real, spec), app.ifft(spec, back)), repeats)
    except Exception as e:  # pragma: no cover
        print(f"pyvkfft: failed on {real.shape}: {e}")
        return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--grids", default="256,512,1024,2048")
    ap.add_argument("--repeats", type=int, default=50)
    ap.add_argument("--out", default="cufft.csv")
    args = ap.parse_args()

    # Copy bandwidth: read + write of a 1 GiB buffer.
    src = cp.zeros(1 << 28, dtype=cp.float32)
    dst = cp.empty_like(src)
    ms = timed(lambda: cp.copyto(dst, src), args.repeats)
    bandwidth = 2 * src.nbytes / (ms * 1e-3)
    print(f"device: {cp.cuda.runtime.getDeviceProperties(0)['name'].decode()}")
    print(f"copy bandwidth: {bandwidth / 1e9:.0f} GB/s (read + write)")
    del src, dst

    rows = []
    for n in (int(g) for g in args.grids.split(",")):
        p = cp.random.standard_normal((n, n), dtype=cp.float32)
        symbol = cp.random.standard_normal((2 * n, n + 1), dtype=cp.float32)

        def convolve():
            spectrum = cp.fft.rfft2(p, s=(2 * n, 2 * n))
            spectrum *= symbol
            return cp.fft.irfft2(spectrum, s=(2 * n, 2 * n))[:n, :n]

        ms = timed(convolve, args.repeats)
        padded = cp.random.standard_normal((2 * n, 2 * n), dtype=cp.float32)
        spectrum = cp.fft.rfft2(padded)
        pair_ms = timed(lambda: (cp.fft.rfft2(padded), cp.fft.irfft2(spectrum, s=(2 * n, 2 * n))), args.repeats)
        vk_ms = vkfft_pair(padded, args.repeats)
        row = {"grid": n, "cufft_convolution_ms": f"{ms:.4f}", "cufft_pair_2n_ms": f"{pair_ms:.4f}",
               "vkfft_pair_2n_ms": "" if vk_ms is None else f"{vk_ms:.4f}",
               "copy_bandwidth_gbs": f"{bandwidth / 1e9:.1f}"}
        rows.append(row)
        vk = "" if vk_ms is None else f", VkFFT R2C+C2R pair {vk_ms:.3f} ms"
        print(f"{n}x{n}: cuFFT padded convolution {ms:.3f} ms, cuFFT R2C+C2R pair on {2 * n}x{2 * n} {pair_ms:.3f} ms{vk}")
        del padded, spectrum

    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"written {args.out}")


if __name__ == "__main__":
    main()
