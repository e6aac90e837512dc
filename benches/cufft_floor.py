#!/usr/bin/env python3
"""cuFFT reference for `jkrbem bench` on an NVIDIA GPU (needs CuPy).

Times, on the same device and in the same run, what one jkrbem convolution does with cuFFT:
the zero-padded real 2-D FFT convolution of an N x N f32 field (rfft2 of 2N x 2N, multiply by a
real spectrum, irfft2, crop), and measures the device's copy bandwidth, so the time per CG
iteration reported by `jkrbem bench --backends gpu` can be set against both.

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
        rows.append({"grid": n, "cufft_convolution_ms": f"{ms:.4f}", "copy_bandwidth_gbs": f"{bandwidth / 1e9:.1f}"})
        print(f"{n}x{n}: cuFFT padded convolution {ms:.3f} ms")

    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"written {args.out}")


if __name__ == "__main__":
    main()
