#!/usr/bin/python3
"""Spectrograms of render.audio, the coin's sound track (Debian's matplotlib and numpy; run with
/usr/bin/python3; needs the ffmpeg command).

Renders two tiny MP4s (64 x 36: only the sound matters) into a temporary folder, each with its
frame times (render --frame-times: the simulated time and playback rate of every frame, as the
program chose them), decodes their AAC tracks with ffmpeg to 48 kHz mono, and writes
  docs/spectrogram.png  (a) the built-in default scene with render.audio = {"frequency_scale": 100}:
                            clicks at 100 x the contact point's rate, pitch "video" (the scene plays
                            at time_scale 0.5, so the heard fundamental is 0.5 * 100 * Omega / 2 pi)
                        (b) examples/euler_disk.json with render.audio = {"pitch": "real"}: clicks
                            at the contact point's own rate Omega / 2 pi, through the time-remapped
                            video (render.time_remap)
each a log-magnitude spectrogram against video time with the theory drawn over it: the fundamental
f = k Omega / 2 pi (times the playback rate for pitch "video") and its first harmonics n f, with
Omega = |phi-dot| = |omega_Y / cos theta| from `coinroll simulate` sampled every millisecond and
read at the frame times the render reported (the time-remap rule is the program's alone).

It also prints, per clip, how far the spectrogram's fundamental lies from the theory, whether every
click of the decoded track falls where the theory's phase crosses a whole cycle, and how much energy
lies above the clicks' 5 kHz band limit (aliasing or block-boundary clicks would show there).

Usage: tools/plot_spectrograms.py [COINROLL] [--output PNG]
       (default: build/coinroll beside this script's folder, docs/spectrogram.png)
"""

import argparse
import io
import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)
import numpy as np  # noqa: E402
from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter  # noqa: E402
from PIL import Image  # noqa: E402  (matplotlib's own dependency)

ROOT = Path(__file__).resolve().parent.parent
RATE = 48000  # Hz, the sound track's sample rate (video::kAudioSampleRate)
BAND_LIMIT = 5000  # Hz, the clicks' harmonics stop here (pipeline::kClickBandLimit)
SAMPLE_DT = 1e-3  # s, CSV rows for Omega(t); linear interpolation between them is exact enough
TINY = ["--set", "render.width=64", "--set", "render.height=36"]

# The built-in default scene's render block (coinroll render without a scene).
DEFAULT_FPS = 30
SCALE_A = 100  # frequency_scale of clip (a): its contact point goes round at ~0.3-0.7 Hz
WINDOW_A, WINDOW_B = 0.12, 0.5  # s, the pictures' Hann windows (resolve 16 Hz and 7 Hz spacings)
CMAP, LINE = "Greys", "red"  # loud is dark; the theory in red over it


def run(command):
    done = subprocess.run([str(c) for c in command], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(map(str, command))} failed ({done.returncode}):\n{done.stderr}")
    return done


def omega_track(coinroll, scene, folder, name):
    """(t, Omega) from coinroll simulate, Omega = |phi-dot| = |omega_Y / cos theta|."""
    csv_path = folder / f"{name}.csv"
    run([coinroll, "simulate", *([scene] if scene else []), "--csv", csv_path, "--sample-dt", repr(SAMPLE_DT)])
    with open(csv_path) as f:
        header = f.readline().strip().split(",")
    table = np.loadtxt(csv_path, delimiter=",", skiprows=1, ndmin=2)
    column = {name: table[:, i] for i, name in enumerate(header)}
    return column["t"], np.abs(column["omega_Y"] / np.cos(column["theta"]))


def render(coinroll, scene, folder, name, audio):
    """Renders the clip's MP4 with its frame-times sidecar; returns the MP4's path and the sidecar's
    columns (frame, video_time_s, clip_frame, sim_time_s, playback_rate)."""
    mp4, sidecar = folder / f"{name}.mp4", folder / f"{name}_frames.csv"
    run([coinroll, "render", *([scene] if scene else []), "-q", "-o", mp4, "--frame-times", sidecar, *TINY,
         "--set", "render.audio=" + json.dumps(audio)])
    table = np.genfromtxt(sidecar, delimiter=",", names=True)
    return mp4, {name: table[name] for name in table.dtype.names}


def sample_frequency(frame_hz, fps):
    """The synthesiser's fundamental at each sample: the block between frames k-1 and k (samples
    k-1 .. k times RATE / fps) glides linearly from frame k-1's frequency to frame k's, and the last
    frame's block holds its frequency."""
    starts = np.arange(len(frame_hz) + 1) * RATE // fps
    values = np.append(frame_hz, frame_hz[-1])
    return np.interp(np.arange(starts[-1]), starts, values)


def decode(mp4, folder, frames, fps):
    """The decoded track, cut to the `frames` frames the sidecar lists (k RATE / fps samples each
    frame starts at): the decoder pads the last AAC frame (1024 samples) with silence, and a track
    that differs by more than that from the sidecar's frames is an error."""
    raw = folder / (mp4.stem + ".raw")
    run(["ffmpeg", "-v", "error", "-y", "-i", mp4, "-f", "f32le", "-ac", "1", "-ar", RATE, raw])
    audio = np.fromfile(raw, dtype=np.float32)
    samples = frames * RATE // fps
    if not samples <= len(audio) < samples + 1024:
        sys.exit(f"{mp4.name}: {len(audio)} decoded samples, but its {frames} frames at {fps} fps last {samples}")
    return audio[:samples].astype(np.float64)


def spectrogram(audio, f_hz, window_s, columns, f_max, pad=4):
    """Hann-windowed STFT with about `columns` frames. Returns frame centres [s], bin frequencies
    [Hz] up to f_max, the power re a full-scale sine, and the theory fundamental averaged over each
    window."""
    n = int(window_s * RATE)
    hop = max(1, (len(audio) - n) // columns)
    nfft = 1 << (pad * n - 1).bit_length()
    freqs = np.fft.rfftfreq(nfft, 1 / RATE)
    keep = freqs <= f_max
    window = np.hanning(n)
    starts = np.arange(0, len(audio) - n + 1, hop)
    power = np.empty((keep.sum(), len(starts)))
    mean_f = np.empty(len(starts))
    for first in range(0, len(starts), 128):  # in chunks: a whole clip at once would not fit
        chunk = starts[first:first + 128]
        segments = np.stack([audio[s:s + n] for s in chunk]) * window
        spectrum = np.abs(np.fft.rfft(segments, nfft, axis=1))[:, keep] * 2 / window.sum()
        power[:, first:first + len(chunk)] = (spectrum ** 2).T
        mean_f[first:first + len(chunk)] = [np.dot(window, f_hz[s:s + n]) / window.sum() for s in chunk]
    return (starts + n / 2) / RATE, freqs[keep], power, mean_f


def log_rows(freqs, power, f_low, f_high, rows, fine=4):
    """The power on `rows` log-spaced bands, each a triangle-weighted mean over the neighbouring
    band on either side (FFT bins averaged on a grid `fine` times finer, or where a band is narrower
    than a bin, interpolated at its centre). Picking one bin per screen row instead would let the
    dense comb of high harmonics beat with the pixel grid into false stripes."""
    edges = np.geomspace(f_low, f_high, rows * fine + 1)
    first = np.searchsorted(freqs, edges)
    counts = np.diff(first)
    sums = np.add.reduceat(power, np.minimum(first[:-1], len(freqs) - 1), axis=0)
    position = np.sqrt(edges[:-1] * edges[1:]) / freqs[1]
    below = np.minimum(np.floor(position).astype(int), len(freqs) - 2)
    weight = (position - below)[:, None]
    interpolated = power[below] * (1 - weight) + power[below + 1] * weight
    banded = np.where((counts > 0)[:, None], sums / np.maximum(counts, 1)[:, None], interpolated)
    triangle = np.convolve(np.ones(fine), np.ones(fine)) / fine ** 2  # 2 bands wide at its foot
    padded = np.pad(banded, ((fine - 1, fine), (0, 0)), mode="edge")
    smooth = sum(w * padded[i:i + len(banded)] for i, w in enumerate(triangle))
    return edges[::fine], smooth[fine // 2::fine]


def ridge(freqs, power, mean_f):
    """The spectrogram's fundamental: the loudest bin within 25 % of the theory's, refined by a
    parabola through the bin and its neighbours."""
    found = np.full(len(mean_f), np.nan)
    for j, f in enumerate(mean_f):
        band = np.flatnonzero((freqs > 0.75 * f) & (freqs < 1.25 * f))
        if len(band) < 3 or band[0] == 0:
            continue
        i = band[np.argmax(power[band, j])]
        a, b, c = np.log(power[i - 1:i + 2, j])
        shift = 0.5 * (a - c) / (a - 2 * b + c) if a - 2 * b + c < 0 else 0
        found[j] = freqs[i] + shift * (freqs[1] - freqs[0])
    return found


def click_check(audio, f_hz):
    """Do the decoded clicks fall where the theory's phase (the integral of f) crosses a whole
    cycle? Returns (clicks the theory predicts, clicks found, largest offset [samples])."""
    phase = np.concatenate([[0], np.cumsum(f_hz / RATE)[:-1]])
    cycle = np.floor(phase)
    crossing = np.flatnonzero(np.diff(cycle) > 0) + 1  # first sample of a new cycle
    before = phase[crossing] - cycle[crossing] > cycle[crossing] - phase[crossing - 1]
    predicted = np.where(before, crossing - 1, crossing)
    fade = int(0.02 * RATE)  # the 5 ms fades (and the clicks' own ringing) at either end
    predicted = predicted[(predicted > fade) & (predicted < len(audio) - fade)]
    level = 0.6 * np.max(audio)
    inner = audio[1:-1]
    peaks = np.flatnonzero((inner > audio[:-2]) & (inner >= audio[2:]) & (inner > level)) + 1
    peaks = peaks[(peaks > fade) & (peaks < len(audio) - fade)]
    if len(peaks) == 0:
        return len(predicted), 0, math.inf
    nearest = np.clip(np.searchsorted(predicted, peaks), 1, len(predicted) - 1)
    offset = np.minimum(np.abs(peaks - predicted[nearest - 1]), np.abs(peaks - predicted[nearest]))
    return len(predicted), len(peaks), int(offset.max())


def above_band(audio, f_min):
    """Energy above f_min [Hz] relative to the whole track, dB."""
    power = np.abs(np.fft.rfft(audio)) ** 2
    freqs = np.fft.rfftfreq(len(audio), 1 / RATE)
    return 10 * np.log10(power[freqs > f_min].sum() / power.sum() + 1e-30)


def report(label, audio, f_hz, times, mean_f, found):
    deviation = np.abs(found / mean_f - 1)
    deviation = deviation[np.isfinite(deviation)]
    worst = np.nanargmax(np.abs(found / mean_f - 1))
    predicted, peaks, offset = click_check(audio, f_hz)
    print(f"{label}: {len(audio) / RATE:.2f} s of sound, fundamental {f_hz.min():.2f}-{f_hz.max():.2f} Hz")
    print(f"  spectrogram fundamental vs theory: median {100 * np.median(deviation):.2f} %, "
          f"99th percentile {100 * np.percentile(deviation, 99):.2f} %, worst {100 * deviation.max():.2f} % "
          f"at {times[worst]:.2f} s ({found[worst]:.2f} Hz against {mean_f[worst]:.2f} Hz)")
    print(f"  clicks: {peaks} found, {predicted} predicted by the phase integral, largest offset {offset} samples")
    print(f"  energy above 5.5 kHz: {above_band(audio, 1.1 * BAND_LIMIT):.1f} dB, "
          f"above 8 kHz: {above_band(audio, 8000):.1f} dB re the whole track")


def harmonic_lines(ax, times, f_hz, f_low, f_high, legend, harmonics):
    for n in range(1, harmonics + 1):
        y = n * f_hz
        ax.plot(times, np.where((y >= f_low) & (y <= f_high), y, np.nan), color=LINE,
                lw=1.0 if n == 1 else 0.6, ls="-" if n == 1 else (0, (6, 2)),
                label=legend if n == 1 else (f"its harmonics n f, n = 2 ... {harmonics}" if n == 2 else None))


def draw(ax, spectrum, f_times, f_hz, f_low, f_high, duration, title, legend, harmonics, rows=360, floor_db=60):
    """A spectrogram on a log frequency axis up to `duration` s of video, with the theory's lines
    n f (n = 1 .. harmonics)."""
    times, freqs, power = spectrum[:3]
    edges, banded = log_rows(freqs, power, f_low, f_high, rows)
    level = 10 * np.log10(banded + 1e-20)
    top = np.percentile(level, 99.5)
    hop = times[1] - times[0]
    mesh = ax.pcolormesh(np.append(times - hop / 2, times[-1] + hop / 2), edges, level, shading="flat",
                         cmap=CMAP, vmin=top - floor_db, vmax=top, rasterized=True)
    harmonic_lines(ax, f_times, f_hz, f_low, f_high, legend, harmonics)
    ax.set_yscale("log")
    ax.set_ylim(f_low, f_high)
    ax.set_xlim(0, duration)
    ticks = [t for t in (2, 3, 5, 7, 10, 15, 20, 30, 50, 70, 100, 150, 200, 300, 500, 700, 1000, 1500, 2000)
             if f_low <= t <= f_high]
    ax.yaxis.set_major_locator(FixedLocator(ticks))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("video time τ [s]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_title(title, fontsize=10)
    ax.legend(loc="upper left", fontsize=8, framealpha=0.85)
    ax.figure.colorbar(mesh, ax=ax, pad=0.015, label="level [dB re full-scale sine]")
    return ax


def save_small(figure, path, dpi=80, colors=128):
    """A palette PNG: the grey spectrograms and the red lines need no more, and the file
    is a fraction of matplotlib's RGBA one."""
    buffer = io.BytesIO()
    figure.savefig(buffer, dpi=dpi, format="png")
    buffer.seek(0)
    Image.open(buffer).convert("RGB").quantize(colors, dither=Image.Dither.NONE).save(path, optimize=True)


def main():
    started = time.monotonic()
    parser = argparse.ArgumentParser(description="Spectrograms of render.audio.")
    parser.add_argument("coinroll", nargs="?", type=Path, default=ROOT / "build" / "coinroll")
    parser.add_argument("--output", type=Path, default=ROOT / "docs" / "spectrogram.png")
    args = parser.parse_args()
    coinroll = args.coinroll
    euler = ROOT / "examples" / "euler_disk.json"
    fps_b = json.loads(euler.read_text())["render"]["fps"]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        # (a) the built-in scene, pitch "video": heard f = playback rate * k * Omega / 2 pi.
        mp4, frames_a = render(coinroll, None, folder, "A", {"frequency_scale": SCALE_A})
        t, omega = omega_track(coinroll, None, folder, "a")
        times_a = frames_a["sim_time_s"]
        hz_a = frames_a["playback_rate"] * SCALE_A * np.interp(times_a, t, omega) / (2 * np.pi)
        f_a = sample_frequency(hz_a, DEFAULT_FPS)
        audio_a = decode(mp4, folder, len(times_a), DEFAULT_FPS)
        # (b) Euler's disk, pitch "real": heard f = Omega / 2 pi at the frame's simulated time, and
        # silence while the landing is held (playback rate 0).
        mp4, frames_b = render(coinroll, euler, folder, "B", {"pitch": "real"})
        t, omega = omega_track(coinroll, euler, folder, "b")
        times_b = frames_b["sim_time_s"]
        hz_b = np.where(frames_b["playback_rate"] > 0, np.interp(times_b, t, omega) / (2 * np.pi), 0)
        f_b = sample_frequency(hz_b, fps_b)
        audio_b = decode(mp4, folder, len(times_b), fps_b)
    rendered = time.monotonic() - started

    tau_a = frames_a["video_time_s"]
    tau_b = frames_b["video_time_s"]
    held = frames_b["playback_rate"] == 0
    video_a, video_b = len(tau_a) / DEFAULT_FPS, len(tau_b) / fps_b  # s
    # The sound ends at the last simulated frame (the block after it is the held landing's silence).
    sounding = (np.count_nonzero(~held) - 1) * RATE // fps_b  # samples
    print(f"(b) frames: {len(times_b)} ({video_b:.2f} s of video at {fps_b} fps, "
          f"{np.count_nonzero(held)} of them the held landing), simulated 0-{times_b[-1]:.3f} s, "
          f"playback rate {frames_b['playback_rate'][~held].min():.4g}-{frames_b['playback_rate'][~held].max():.4g}")
    sa = spectrogram(audio_a, f_a, WINDOW_A, 900, 2000)
    sb = spectrogram(audio_b, f_b, WINDOW_B, 900, 1000)
    # (a)'s pitch swings fast (16 -> 36 Hz in 0.35 s): its fundamental is measured with a longer
    # window than the picture's, which resolves the harmonics better but smears the swings.
    measure = spectrogram(audio_a, f_a, 0.25, 600, 200)
    report("(a) default scene, k = 100, pitch video", audio_a, f_a, measure[0], measure[3],
           ridge(measure[1], measure[2], measure[3]))
    # (b) is judged, and its theory drawn, over the windows that end before the silence: once the
    # disk slips, Omega wobbles by a few per cent from frame to frame, which the sound (synthesised
    # from the frames) carries too, so the theory is drawn as the spectrogram sees it, averaged over
    # each window.
    whole = sb[0] + WINDOW_B / 2 <= sounding / RATE
    report("(b) euler_disk.json, k = 1, pitch real", audio_b[:sounding], f_b[:sounding], sb[0][whole], sb[3][whole],
           ridge(sb[1], sb[2][:, whole], sb[3][whole]))

    figure, (top, bottom) = plt.subplots(2, 1, figsize=(11, 9.5))
    draw(top, sa, tau_a, hz_a, 10, 2000, video_a,
         "(a) built-in default scene, render.audio = {\"frequency_scale\": 100} (pitch \"video\", clicks): "
         f"the wobble heard as a click rate\nswinging between {hz_a.min():.0f} and {hz_a.max():.0f} per second, "
         "0.5 × 100 × Ω / 2π "
         f"(played at time_scale 0.5, so t = τ / 2); Hann window {WINDOW_A} s",
         "theory: fundamental f = 0.5 × 100 × Ω(τ / 2) / 2π", harmonics=3)
    draw(bottom, sb, sb[0][whole], sb[3][whole], 4, 1000, video_b,
         "(b) examples/euler_disk.json, render.audio = {\"pitch\": \"real\"}: clicks at the contact point's "
         "real rate Ω / 2π\n"
         f"through the remapped video: {hz_b[0]:.1f} Hz ticks rising to a {hz_b.max():.0f} Hz buzz, then "
         f"{held.sum() / fps_b:g} s of held landing, silent; Hann window {WINDOW_B} s",
         "theory: fundamental f = Ω(t) / 2π at the frames' simulated times t, averaged over each window",
         harmonics=5)
    simulated = bottom.secondary_xaxis("top", functions=(lambda v: np.interp(v, tau_b, times_b),
                                                         lambda v: np.interp(v, times_b, tau_b)))
    simulated.set_xticks([0, 20, 40, 60, 80, 100, 110, 115])
    simulated.tick_params(labelsize=8)
    simulated.set_xlabel("simulated time t [s]", fontsize=8, labelpad=2)
    figure.tight_layout()
    save_small(figure, args.output)
    print(f"rendering and decoding {rendered:.0f} s, total {time.monotonic() - started:.0f} s; wrote {args.output}")

if __name__ == "__main__":
    main()
