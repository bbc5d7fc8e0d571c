#!/usr/bin/env bash
# video.sh - swarmsim --video: each video's frame count (one every N steps
# from step 0, and the state at the end: ceil(steps / N) + 1) and duration
# (frames / fps) read back with ffprobe; the defaults; a run a task ends
# early; only the first repetition filmed; rendering leaves the run's
# results unchanged; bad arguments and a missing ffmpeg exit 2 before any
# run with nothing written; an ffmpeg that fails mid-way (a fake one on
# PATH) leaves no file, an older file untouched, and says why; the time
# stamp and legend on PNG frames and on video frames.  (About 10 s.)
#
# usage (from anywhere): bash tests/video/video.sh build/swarmsim
set -u
if [ $# -ne 1 ]; then
    echo "usage: $0 path/to/swarmsim" >&2
    exit 2
fi
sim=$1
case $sim in /*) ;; *) sim="$PWD/$sim" ;; esac
cd "$(dirname "$0")/../.." || exit 1
for tool in ffmpeg ffprobe python3; do
    command -v "$tool" >/dev/null || { echo "video.sh: $tool is missing (make deps installs it)" >&2; exit 1; }
done
tmp=$(mktemp -d "${TMPDIR:-/tmp}/video_tests.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
check() { if eval "$2"; then ok; else bad "$1"; fi; }
rw=sim_host/scenarios/random_walk.yaml

# probe FILE: "frames duration width height codec pix_fmt" (frames decoded
# and counted, not the container's claim).
probe() {
    local s f
    s=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries \
        stream=nb_read_frames,width,height,codec_name,pix_fmt -of default=nw=1 "$1") || return 1
    f=$(ffprobe -v error -show_entries format=duration -of default=nw=1:nk=1 "$1") || return 1
    printf '%s %s %s %s %s %s\n' "$(sed -n 's/^nb_read_frames=//p' <<<"$s")" "$f" \
        "$(sed -n 's/^width=//p' <<<"$s")" "$(sed -n 's/^height=//p' <<<"$s")" \
        "$(sed -n 's/^codec_name=//p' <<<"$s")" "$(sed -n 's/^pix_fmt=//p' <<<"$s")"
}

# expect_video NAME FILE FRAMES FPS [W H]: the file decodes to FRAMES
# H.264 yuv420p frames lasting FRAMES / FPS s (to 1 ms), of W x H pixels.
expect_video() {
    local name=$1 file=$2 frames=$3 fps=$4 w=${5:-} h=${6:-} got want
    if [ ! -s "$file" ]; then bad "$name: no video at $file"; return; fi
    if [ -e "$file.tmp" ]; then bad "$name: $file.tmp left behind"; return; fi
    read -r got_frames got_dur got_w got_h codec pix <<<"$(probe "$file")"
    want=$(awk -v n="$frames" -v f="$fps" 'BEGIN { printf "%.3f", n / f }')
    got=$(awk -v d="$got_dur" 'BEGIN { printf "%.3f", d }')
    if [ "$got_frames" != "$frames" ]; then bad "$name: $got_frames frames, expected $frames"
    elif [ "$got" != "$want" ]; then bad "$name: lasts $got s, expected $want s ($frames frames at $fps fps)"
    elif [ "$codec $pix" != "h264 yuv420p" ]; then bad "$name: $codec $pix, expected h264 yuv420p"
    elif [ -n "$w" ] && [ "$got_w x $got_h" != "$w x $h" ]; then bad "$name: ${got_w}x$got_h, expected ${w}x$h"
    else ok; fi
}

# ---- frame count and duration
"$sim" $rw --steps 100 --video-every 10 --video-fps 20 --frame-px 320 --lcm off \
    --out "$tmp/a" --video "$tmp/a.mp4" >/dev/null 2>"$tmp/a.err"
expect_video "100 steps, every 10, 20 fps" "$tmp/a.mp4" 11 20 320 320
check "the end of a run names the video and its frames" \
    "grep -qF 'video $tmp/a.mp4: 11 frames at 20 fps, 0.55 s' '$tmp/a.err'"

# Not a multiple of N, a non-square arena and an odd width: 95 steps give
# frames at 0, 10, ..., 90 and 95; 301 x 248.2 px become 300 x 246.
"$sim" $rw --steps 95 --video-every 10 --video-fps 25 --frame-px 301 --set arena.height=3.3 \
    --lcm off --quiet --out "$tmp/b" --video "$tmp/b.mp4"
expect_video "95 steps, every 10, 25 fps, odd size" "$tmp/b.mp4" 11 25 300 246

# The defaults: every 10 steps at 20 fps (a 1200 s run is 1,201 frames, 60 s).
"$sim" $rw --steps 200 --lcm off --quiet --out "$tmp/c" --video "$tmp/c.mp4" --frame-px 160
expect_video "defaults (every 10, 20 fps)" "$tmp/c.mp4" 21 20

# A task ends the run early: the last frame is the end, ceil(S / N) + 1.
"$sim" sim_host/scenarios/phototaxis_gather.yaml --video-every 7 --frame-px 160 --lcm off --quiet \
    --out "$tmp/g" --video "$tmp/g.mp4"
steps=$(sed -n 's/.*"steps": \([0-9]*\),/\1/p' "$tmp/g/run_1/summary.json")
check "the gather run ends early (steps $steps)" "[ -n '$steps' ] && [ '$steps' -lt 3000 ]"
expect_video "a run a task ended after ${steps:-?} steps" "$tmp/g.mp4" $(((steps + 6) / 7 + 1)) 20

# ---- --reps: the first repetition only, and it is seed N's own video
mkdir -p "$tmp/r"
"$sim" $rw --steps 60 --reps 3 --threads 2 --seed 5 --frame-px 160 --lcm off --quiet \
    --out "$tmp/r/runs" --video "$tmp/r/reps.mp4"
"$sim" $rw --steps 60 --seed 5 --frame-px 160 --lcm off --quiet --out "$tmp/r5" --video "$tmp/r5.mp4"
"$sim" $rw --steps 60 --seed 6 --frame-px 160 --lcm off --quiet --out "$tmp/r6" --video "$tmp/r6.mp4"
expect_video "--reps 3" "$tmp/r/reps.mp4" 7 20
check "--reps 3 wrote one video" "[ \"\$(find '$tmp/r' -name '*.mp4*' | wc -l)\" -eq 1 ]"
check "--reps 3 --seed 5 films seed 5 (the same bytes as --seed 5 alone)" "cmp -s '$tmp/r/reps.mp4' '$tmp/r5.mp4'"
check "seeds 5 and 6 give different videos" "! cmp -s '$tmp/r5.mp4' '$tmp/r6.mp4'"

# ---- rendering only reads the simulation: same summary and time series
fargs=(sim_host/scenarios/foraging_base.yaml --steps 600 --lcm off --quiet)
"$sim" "${fargs[@]}" --out "$tmp/plain"
"$sim" "${fargs[@]}" --out "$tmp/filmed" --video "$tmp/filmed.mp4" --video-every 3 --frame-px 160
for f in summary.json timeseries.csv; do
    # (but the summary's command line, which names the video options)
    check "$f is the same with --video" "cmp -s <(grep -v '^  \"command\": ' '$tmp/plain/run_1/$f') <(grep -v '^  \"command\": ' '$tmp/filmed/run_1/$f')"
done
expect_video "foraging, every 3" "$tmp/filmed.mp4" 201 20

# ---- bad arguments: exit 2, the reason, and nothing written
# expect_refused NAME STDERR-TEXT SWARMSIM-ARGS... runs "${run[@]}" (swarmsim)
mkdir -p "$tmp/x" "$tmp/x/dir.mp4"
run=("$sim")
expect_refused() {
    local name=$1 want=$2 rc
    shift 2
    "${run[@]}" $rw --steps 20 --lcm off --out "$tmp/x/out" "$@" >/dev/null 2>"$tmp/x.err"
    rc=$?
    if [ "$rc" -ne 2 ]; then bad "$name: exit status $rc, expected 2"
    elif ! grep -qF -- "$want" "$tmp/x.err"; then bad "$name: stderr lacks '$want': $(head -2 "$tmp/x.err")"
    elif [ -n "$(ls -A "$tmp/x" | grep -v '^dir.mp4$')" ]; then bad "$name: wrote $(ls -A "$tmp/x" | tr '\n' ' ')"
    else ok; fi
}
v=$tmp/x/v.mp4
expect_refused "not .mp4" "--video: '$tmp/x/v.avi' is not a FILE.mp4 name" --video "$tmp/x/v.avi"
expect_refused "no such folder" "the folder '$tmp/x/missing' does not exist" --video "$tmp/x/missing/v.mp4"
expect_refused "a folder" "--video: '$tmp/x/dir.mp4' is a folder" --video "$tmp/x/dir.mp4"
expect_refused "every 0" "--video-every: '0' is not an integer in [1, 1000000000]" --video "$v" --video-every 0
expect_refused "every not a number" "--video-every: '5s' is not an integer" --video "$v" --video-every 5s
expect_refused "fps 0" "--video-fps: '0' is not a frame rate in [1, 240]" --video "$v" --video-fps 0
expect_refused "fps too high" "--video-fps: '500' is not a frame rate" --video "$v" --video-fps 500
expect_refused "every without --video" "--video-every needs --video FILE.mp4" --video-every 5
expect_refused "fps without --video" "--video-fps needs --video FILE.mp4" --video-fps 30
expect_refused "--video without a value" "--video needs a value" --video
expect_refused "a bad scenario key" "robots.0.cuont" --video "$v" --set robots.0.cuont=3
# No ffmpeg on PATH: refused at startup, naming the package.
mkdir -p "$tmp/bin-empty"
run=(env "PATH=$tmp/bin-empty" "$sim")
expect_refused "ffmpeg missing" "needs ffmpeg, which is not on PATH (Debian package ffmpeg" --video "$v"

# ---- ffmpeg failing: a fake ffmpeg on PATH.  An older video at the same
# name must survive, and no .tmp may be left.
mkdir -p "$tmp/fake" "$tmp/f"
cp "$tmp/c.mp4" "$tmp/f/v.mp4"
# fake_ffmpeg BEHAVIOUR: write a fake that reads some input, writes a
# partial file at its output path (its last argument), and exits.
fake_ffmpeg() {
    cat >"$tmp/fake/ffmpeg" <<EOF
#!/bin/sh
for a; do out=\$a; done
$1
EOF
    chmod +x "$tmp/fake/ffmpeg"
}
# expect_ffmpeg_failure NAME STDERR-TEXT...: the run exits 1 with those
# texts on stderr, v.mp4 is still the older video, no v.mp4.tmp.
expect_ffmpeg_failure() {
    local name=$1 rc want
    shift
    PATH="$tmp/fake:$PATH" "$sim" $rw --steps 400 --video-every 1 --frame-px 160 --lcm off --quiet \
        --out "$tmp/f/out" --replace --video "$tmp/f/v.mp4" 2>"$tmp/f.err"
    rc=$?
    if [ "$rc" -ne 1 ]; then bad "$name: exit status $rc, expected 1"; return; fi
    for want in "$@"; do
        grep -qF -- "$want" "$tmp/f.err" || { bad "$name: stderr lacks '$want': $(head -2 "$tmp/f.err")"; return; }
    done
    if [ -e "$tmp/f/v.mp4.tmp" ]; then bad "$name: v.mp4.tmp left behind"
    elif ! cmp -s "$tmp/c.mp4" "$tmp/f/v.mp4"; then bad "$name: the older v.mp4 was replaced"
    else ok; fi
}
# 160 x 160 x 3 = 76,800 bytes a frame: it dies within the 4th.
fake_ffmpeg 'head -c 250000 >/dev/null; echo partial >"$out"; echo "fake ffmpeg: No space left on device" >&2; exit 1'
expect_ffmpeg_failure "ffmpeg dies mid-way" "$tmp/f/v.mp4: ffmpeg exited with status 1 after " \
    "fake ffmpeg: No space left on device"
fake_ffmpeg 'head -c 250000 >/dev/null; exit 0'
expect_ffmpeg_failure "ffmpeg stops reading" "$tmp/f/v.mp4: ffmpeg stopped reading after "
fake_ffmpeg 'cat >/dev/null; echo partial >"$out"; echo "fake ffmpeg: cannot write the trailer" >&2; exit 1'
expect_ffmpeg_failure "ffmpeg fails at the end" "ffmpeg exited with status 1 after 401 frame(s)" \
    "fake ffmpeg: cannot write the trailer"
fake_ffmpeg 'kill -9 $$'
expect_ffmpeg_failure "ffmpeg killed" "ffmpeg was killed by signal 9"

# ---- the time stamp and the legend, on PNG frames and video frames
# rgb FILE: its first picture as raw RGB bytes on stdout.
rgb() { ffmpeg -v error -i "$1" -frames:v 1 -f rawvideo -pix_fmt rgb24 -; }
"$sim" sim_host/scenarios/foraging_base.yaml --steps 10 --frames 10 --frame-px 400 --lcm off --quiet \
    --out "$tmp/p" --video "$tmp/p.mp4" --video-every 10
rgb "$tmp/p/run_1/frames/frame_000000.png" >"$tmp/p0.rgb"
rgb "$tmp/p/run_1/frames/frame_000010.png" >"$tmp/p10.rgb"
rgb "$tmp/p.mp4" >"$tmp/v0.rgb"
# The band is the rows above the wall's first row in the middle column.
# PNG frames: the text colour and the swatch of every key of the foraging
# legend (waiting = the default body, searching, returning, the beacon)
# are in it; frames at t = 0 and 1 s differ there, in the left third (the
# time stamp).  The video's first frame (lossy) has the text there too.
python3 - "$tmp/p0.rgb" "$tmp/p10.rgb" "$tmp/v0.rgb" >"$tmp/band.out" <<'EOF'
import sys
W = H = 400
def load(path):
    d = open(path, 'rb').read()
    assert len(d) == W * H * 3, (path, len(d))
    return d
def px(d, x, y):
    i = (y * W + x) * 3
    return d[i] << 16 | d[i + 1] << 8 | d[i + 2]
p0, p10, v0 = (load(p) for p in sys.argv[1:4])
band = next(y for y in range(H) if px(p0, W // 2, y) == 0x3C3C46)
colours = {px(p0, x, y) for y in range(band) for x in range(W)}
for name, rgb in [('text', 0x10101A), ('waiting', 0xAFBED2), ('searching', 0x8CDC8C),
                  ('returning', 0xF0DC5A), ('beacon', 0x8CA0F0)]:
    print(name, 'yes' if rgb in colours else 'no')
diff = [x for y in range(band) for x in range(W) if px(p0, x, y) != px(p10, x, y)]
print('time', 'yes' if diff and max(diff) < W // 3 else 'no')
dark = sum(1 for y in range(band) for x in range(W) if sum(v0[(y * W + x) * 3 + k] for k in range(3)) < 200)
print('video', 'yes' if dark > 100 else 'no')
print('band', band)
EOF
for item in text waiting searching returning beacon time video; do
    check "PNG/video band: $item ($(tr '\n' ' ' <"$tmp/band.out"))" "grep -qx '$item yes' '$tmp/band.out'"
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
