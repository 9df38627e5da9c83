"""bench/report.py's tables of particle files (load-ply/, big/, formats/ rows) and of
trajectories (frames/ rows)."""
from report_common import of_kind

def print_particle_files(rows):
    """load-ply/N against the JSON load/N rows (the cloud's text) and the bare bandwidths; big/ rows."""
    ply = {int(r.spheres): r for r in of_kind(rows, "load-ply") if not r.error}
    json_rows = {int(r.spheres): r for r in of_kind(rows, "load") if not r.error}
    if ply:
        print("\nParticle files (load-ply/): a PLY file of the packed box (19 bytes a sphere) from the page cache;\n"
              "ns a sphere (medians)\n"
              "         N    PLY load    GB/s   pread  memcpy   prepare   JSON parse (load/, the cloud's text)")
        for n in sorted(ply):
            r, j = ply[n], json_rows.get(n)
            print(f"  {n:8d}" + "".join(f"{r.get(k, 0):10.1f}" if k != "load_GBps" else f"{r.get(k, 0):8.2f}"
                                          for k in ("load_ns_per_sphere", "load_GBps")) +
                  "".join(f"{r.get(k, 0):8.2f}" for k in ("pread_ns_per_sphere", "memcpy_ns_per_sphere")) +
                  f"{r.get('prepare_ns_per_sphere', 0):10.1f}" +
                  (f"{j.get('parse_ns_per_sphere'):13.1f}" if j and "parse_ns_per_sphere" in j else "            -"))
        print("  pread: the same file read into memory; memcpy: its bytes copied; the load reads, checks every\n"
              "  value and fills the scene's columns (first touch of fresh memory included)")
    for r in of_kind(rows, "big"):
        if r.error:
            print(f"\n{r.name}: {r.error}")
            continue
        print(f"\n{r.name} (3840x2160, all cores, raycast end to end): load {r.get('load_s', 0):.2f} s, prepare "
              f"{r.get('prepare_s', 0):.2f} s, render {r.get('render_s', 0):.2f} s, total {r.get('total_s', 0):.2f} s, "
              f"peak RSS {r.get('peak_rss_mb', 0) / 1e3:.2f} GB")


def print_formats(rows):
    """formats/ rows: one frame of each particle format by our readers, against numpy, ASE and zlib alone."""
    frame = [r for r in of_kind(rows, "formats") if not r.family.startswith("trajectory")]
    if not frame:
        return
    by = {(r.family, r.reader): r for r in frame}
    print("\nParticle formats (formats/): one frame from the page cache, every column, one thread (a .gz: one more\n"
          "inflating ahead); medians; cpu: the CPU seconds of the process (less swayed by other work on the machine).\n"
          "Goals: 0.1 s and 5x numpy, 40x ASE for the 10^6-atom dump; 0.8x zlib's own speed gzipped; 1 GB/s for GSD")
    print("  family       atoms  reader         seconds       cpu      MB/s   against")
    for r in sorted(frame, key=lambda r: (r.family, r.reader != "ours", r.reader)):
        if r.error:
            print(f"  {r.family:10s} {r.atoms:>7s}  {r.reader:12s}  {r.error}")
            continue
        ours = by.get((r.family, "ours"))
        against = ""
        if r.reader in ("numpy", "ase") and ours and not ours.error and ours.get("seconds"):
            against = f"ours {r.seconds / ours.seconds:.1f}x faster"
            if r.get("cpu_seconds") and ours.get("cpu_seconds"):
                against += f" ({r.cpu_seconds / ours.cpu_seconds:.1f}x in CPU seconds)"
        if r.reader == "ours" and r.family == "lammps-gz":
            z = by.get(("lammps-gz", "inflate"))
            if z and not z.error and z.get("MBps"):
                against = f"{r.MBps / z.MBps:.2f}x zlib's own speed"
        print(f"  {r.family:10s} {r.atoms:>7s}  {r.reader:12s} {r.get('seconds', 0):8.4f}  {r.get('cpu_seconds', 0):8.4f}"
              f" {r.get('MBps', 0):9.0f}   {against}")
    traj = {(r.family, int(r.frames)): r for r in of_kind(rows, "formats") if r.family.startswith("trajectory")}
    for family in sorted({f for f, _ in traj}):
        one, many = traj.get((family, 1)), [traj[k] for k in sorted(traj) if k[0] == family and k[1] > 1]
        for r in many:
            if r.error or not one or one.error:
                print(f"  {family}: {r.error or (one.error if one else 'no one-frame row')}")
                continue
            f = int(r.frames)
            print(f"  {family} ({r.atoms} atoms a frame): {f} frames in order {r.seconds:.3f} s = "
                  f"{r.seconds / (f * one.seconds):.2f} x {f} x one frame ({one.seconds:.4f} s); resident memory grew "
                  f"{r.get('rss_growth_mb', 0):.1f} MB over the frames; peak RSS {r.get('peak_rss_mb', 0):.0f} MB")


def print_frames(rows):
    """frames/ rows: raycast over an F-frame trajectory against its one-frame run, from their --stats."""
    fr = [r for r in of_kind(rows, "frames")]
    if not fr:
        return
    print("\nTrajectories (frames/): raycast --scene DUMP -o f_%04d.png --threads 1 against --frames 0 of the same\n"
          "file, from their --stats (medians); one frame's work = its prepare + render (+ write: the PNG).\n"
          "Goals: F frames <= 1.1 x (F x one frame's prepare + render) + one frame's load; peak RSS <= 1.6x one frame's")
    print(f"  {'atoms':>7} {'frames':>6} {'size':>9} {'total s':>8} {'1 frame s':>9} {'vs goal':>8} "
          f"{'vs frames+writes':>16} {'peak MB':>8} {'x 1 frame':>9}")
    for r in sorted(fr, key=lambda r: (int(r.frames), int(r.atoms))):
        if r.error:
            print(f"  {r.atoms:>7} {r.frames:>6} {r.size:>9}  {r.error}")
            continue
        f = int(r.frames)
        work = r.one_prepare + r.one_render
        goal = r.seconds / (f * work + r.one_load) if work > 0 else float("nan")
        # The one-frame run and F - 1 more frames, each written as its own PNG.
        expected = r.one_seconds + (f - 1) * (work + r.one_write)
        print(f"  {r.atoms:>7} {f:>6} {r.size:>9} {r.seconds:8.3f} {r.one_seconds:9.4f} {goal:7.2f}x "
              f"{r.seconds / expected:15.2f}x {r.peak_rss_mb:8.0f} {r.peak_rss_mb / r.one_peak_rss_mb:8.2f}x")
    print("  vs goal: total / (F x (prepare + render) + load) of one frame, the total with the program's start (the\n"
          "  image library's load) and every PNG's writing; vs frames+writes: total / (the one-frame run + F - 1 frames'\n"
          "  prepare + render + write)")
