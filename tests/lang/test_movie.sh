#!/bin/sh
# test_movie.sh — `sinew-plot frames` and `sinew-plot movie`: a real run's
# rods drawn frame by frame and encoded by ffmpeg, checked by what the
# pictures and the video hold, and bad input gives one clear line.
#
#   frames   examples/pendulum.sinew run for 0.3 s (frames every 1 ms),
#            seen along +y (--view 0,-90), so the image is the x-z plane of
#            the swing: the rod's pixels are found by its colour, their
#            centroid must move by the run's own centre-of-rod displacement
#            times the picture's scale (measured from the rod's length in
#            pixels), and the rod must be as wide as its diameter at that
#            scale
#   movie    ffprobe counts the frames (real time at 30 fps; --fps and
#            --speed; the 300-frame cap on a synthetic 20 s run), and
#            reports the size and codec (h264 from libx264, or mpeg4)
#   errors   one line and the exit code for a file without rods, a missing
#            file, no ffmpeg on PATH, bad options, an unwritable movie; Ctrl-C
#            exits 130 and leaves neither a partial movie nor an ffmpeg
#
# ffmpeg is not one of `make test`'s base packages: this test installs it
# when it is missing (scripts/deps.sh ffmpeg:/usr/bin/ffmpeg); its absence
# after that is a failure, not a skip.
. "$(dirname "$0")/tap.sh"
cd "$ROOT" || exit 1
PLOT=$ROOT/scripts/sinew-plot
PY=/usr/bin/python3
scratch movie

sh scripts/deps.sh ffmpeg:/usr/bin/ffmpeg >"$TMP/log" 2>&1
[ -x /usr/bin/ffmpeg ] && [ -x /usr/bin/ffprobe ]
ok $? "ffmpeg and ffprobe are installed (scripts/deps.sh ffmpeg:/usr/bin/ffmpeg)"
diag <"$TMP/log"

"$SINEWC" examples/pendulum.sinew -o "$TMP/pend" >"$TMP/log" 2>&1 &&
  "$TMP/pend" --quiet --duration 0.3s --every 1ms --out "$TMP/pend.h5" >>"$TMP/log" 2>&1
ok $? "pendulum.sinew compiles and runs 0.3 s, a frame every 1 ms"
diag <"$TMP/log"

# ---- frames
"$PLOT" frames "$TMP/pend.h5" -o "$TMP/frames" --every 50 --view 0,-90 --size 640x480 \
  >"$TMP/log" 2>&1
ok $? "frames --every 50 --view 0,-90 --size 640x480"
diag <"$TMP/log"
n=$(ls "$TMP/frames" | grep -c '^frame_[0-9]\{5\}\.png$')
[ "$n" -eq 7 ]
ok $? "7 frames of 301 at --every 50 (frame_00000.png ... frame_00006.png): $n"

# The rod's pixels: those within 60 (of 255, Euclidean in RGB) of its
# colour, #2f6da8 (KIND_COLOURS["rod"]), left of the legend (the right
# fifth of the picture, where a line of that colour names the kind).  Seen along +y with an orthographic
# camera, image column = x and image row = -z, at one scale s (px/m).
$PY - "$TMP" <<'EOF' >"$TMP/measure" 2>"$TMP/log"
import sys, h5py, numpy as np
from matplotlib.image import imread
d = sys.argv[1]
def rod_pixels(png):
    img = imread(png)[:, :, :3] * 255
    mask = np.linalg.norm(img - np.array([0x2f, 0x6d, 0xa8]), axis=2) < 60
    mask[:, int(0.8 * img.shape[1]):] = False
    rows, cols = np.nonzero(mask)
    return img.shape, rows, cols
with h5py.File(f"{d}/pend.h5", "r") as f:
    x = f["rods/bar/position"][()]
    r = float(np.ravel(f["rods/bar"].attrs["radius"])[0])
shape0, rows0, cols0 = rod_pixels(f"{d}/frames/frame_00000.png")
shape6, rows6, cols6 = rod_pixels(f"{d}/frames/frame_00006.png")
# scale from the first frame: the rod's height in pixels is its z extent
# plus the round caps (a diameter), times s
height = rows0.max() - rows0.min() + 1
zext = x[0, :, 2].max() - x[0, :, 2].min()
s = height / (zext + 2 * r)
# centroid of a uniform capsule: the midpoint of its axis, the mean of the
# evenly spaced nodes
moved = cols6.mean() - cols0.mean()
expect = (x[300, :, 0].mean() - x[0, :, 0].mean()) * s
# width across the rod at its middle row in the last frame (the rod is
# within 1 degree of vertical there)
mid = (rows6.min() + rows6.max()) // 2
width = np.count_nonzero(rows6 == mid)
print(shape0[1], shape0[0], len(rows0), len(rows6), f"{s:.1f}", f"{moved:.2f}",
      f"{expect:.2f}", width, f"{2 * r * s:.2f}")
EOF
ok $? "the frames are read back"
diag <"$TMP/log"
read -r w h n0 n6 s moved expect width diam <"$TMP/measure"
echo "# frame ${w}x${h}; rod pixels first/last $n0/$n6; scale $s px/m;" \
  "centroid moved $moved px (data: $expect px); width $width px (diameter: $diam px)"
[ "$w" = 640 ] && [ "$h" = 480 ]
ok $? "the frames are 640x480: ${w}x${h}"
[ "$n0" -gt 1000 ] && [ "$n6" -gt 1000 ]
ok $? "the rod is drawn in the first and last frame: $n0 and $n6 pixels of its colour"
awk -v m="$moved" -v e="$expect" 'BEGIN { d = m - e; if (d < 0) d = -d; exit !(e < -20 && d < 2) }'
ok $? "the rod swings: its centroid moved $moved px, the run's rod centre $expect px (within 2 px)"
awk -v w="$width" -v d="$diam" 'BEGIN { x = w - d; if (x < 0) x = -x; exit !(x <= 2) }'
ok $? "the rod is as wide as its diameter: $width px against 2 r s = $diam px (within 2 px)"

# ---- movie
probe() {   # probe FILE: "codec width height frames rate" of the first video stream
  ffprobe -v error -count_frames -select_streams v:0 \
    -show_entries stream=codec_name,width,height,nb_read_frames,r_frame_rate \
    -of default=noprint_wrappers=1 "$1" |
    awk -F= '{ v[$1] = $2 } END { print v["codec_name"], v["width"], v["height"], v["nb_read_frames"], v["r_frame_rate"] }'
}
# movie DESCRIPTION EXPECTED ARGS...: exits 0 and ffprobe says EXPECTED
movie() {
  what=$1 want=$2; shift 2
  rm -f "$TMP/out.mp4"
  "$PLOT" movie "$@" -o "$TMP/out.mp4" >"$TMP/log" 2>&1
  rc=$?
  got=$(probe "$TMP/out.mp4" 2>>"$TMP/log")
  got_codec=${got%% *}
  case $got_codec in h264|mpeg4) want="$got_codec $want" ;; esac
  [ $rc -eq 0 ] && [ "$got" = "$want" ]
  ok $? "$what: ffprobe says '$got'"
  [ $rc -eq 0 ] && [ "$got" = "$want" ] || { echo "exit $rc; expected '$want'"; cat "$TMP/log"; } | diag
}
mkdir "$TMP/tmpdir"
TMPDIR=$TMP/tmpdir movie "real time at 30 fps: 0.3 s is 9 intervals, 10 frames" \
  "320 240 10 30/1" "$TMP/pend.h5" --size 320x240
n=$(ls -A "$TMP/tmpdir" | wc -l)
[ "$n" -eq 0 ]
ok $? "the movie leaves no temporary file ($n in TMPDIR)"
movie "--fps 20 --speed 0.5: 0.6 s of movie, 13 frames" "640 480 13 20/1" \
  "$TMP/pend.h5" --fps 20 --speed 0.5 --size 640x480 --view 10,-80

# a 20 s run: 600 frames at 30 fps, so 300 at 299/20 fps
$PY - "$TMP" <<'EOF' 2>"$TMP/log"
import sys, h5py, numpy as np
d = sys.argv[1]
t = np.linspace(0, 20, 2001)
with h5py.File(f"{d}/long.h5", "w") as f:
    f["time"] = t
    x = np.zeros((len(t), 5, 3))
    x[:, :, 0] = np.linspace(0, 1, 5) * np.sin(0.3 * np.sin(t))[:, None]
    x[:, :, 2] = -np.linspace(0, 1, 5) * np.cos(0.3 * np.sin(t))[:, None]
    f["rods/stick/position"] = x
    f["rods/stick"].attrs["radius"] = np.full(4, 0.02)
with h5py.File(f"{d}/norods.h5", "w") as f:
    f["time"] = t
    f["joints/pivot/angle"] = np.zeros_like(t)
EOF
ok $? "h5py writes a 20 s run and a file without rods"
diag <"$TMP/log"
movie "a 20 s run without --fps: capped at 300 frames, at 299/20 fps to keep real time" \
  "160 120 300 299/20" "$TMP/long.h5" --size 160x120
grep -q "^sinew-plot: note: 300 frames at 14.9 fps play the 20 s run at speed 1; give --fps for more$" \
  "$TMP/log"
ok $? "the capped movie says so in a note"
"$PLOT" frames "$TMP/long.h5" -o "$TMP/longframes" --size 64x48 >"$TMP/log" 2>&1
n=$(ls "$TMP/longframes" | grep -c '^frame_[0-9]\{5\}\.png$')
[ "$n" -eq 300 ]
ok $? "frames of the 2001 frames of the 20 s run: 300 spread evenly ($n)"
diag <"$TMP/log"

# ---- bad input: one line, the right exit code, no traceback, no output
# fails CODE MESSAGE DESCRIPTION ARGS...
# (with $RUN before the command when set: ffmpeg hidden from PATH below)
RUN=
fails() {
  code=$1 msg=$2 what=$3; shift 3
  rm -f "$TMP/x.mp4"
  $RUN "$PLOT" "$@" >"$TMP/log" 2>&1
  rc=$?
  last=$(tail -n 1 "$TMP/log")
  [ $rc -eq "$code" ] && [ "$last" = "$msg" ] && ! grep -q Traceback "$TMP/log" &&
    [ ! -e "$TMP/x.mp4" ]
  res=$?
  ok $res "$what: exit $code, \"$msg\""
  [ $res -eq 0 ] || { echo "exit $rc"; cat "$TMP/log"; } | diag
}
fails 4 "sinew-plot: $TMP/norods.h5: no rods (no dataset /rods/NAME/position)" \
  "movie of a file without rods" movie "$TMP/norods.h5" -o "$TMP/x.mp4"
fails 4 "sinew-plot: $TMP/norods.h5: no rods (no dataset /rods/NAME/position)" \
  "frames of a file without rods" frames "$TMP/norods.h5" -o "$TMP/xframes"
fails 4 "sinew-plot: $TMP/none.h5: no such file" "missing file" movie "$TMP/none.h5" -o "$TMP/x.mp4"
# ffmpeg out of reach: an empty PATH (the script's interpreter is absolute)
mkdir "$TMP/nobin"
RUN="env PATH=$TMP/nobin"
fails 1 "sinew-plot: ffmpeg is missing: install Debian's ffmpeg package (apt-get install ffmpeg)" \
  "movie without ffmpeg on PATH" movie "$TMP/pend.h5" -o "$TMP/x.mp4"
RUN=
fails 2 "sinew-plot: --size 321x240: the movie's width and height must be even (4:2:0 video)" \
  "odd movie size" movie "$TMP/pend.h5" --size 321x240 -o "$TMP/x.mp4"
fails 2 "sinew-plot: --view takes ELEV,AZIM in degrees (e.g. 20,-60), got '20'" \
  "bad --view" movie "$TMP/pend.h5" --view 20 -o "$TMP/x.mp4"
fails 2 "sinew-plot: --size takes WIDTHxHEIGHT in pixels, 16 to 8192 (e.g. 800x600), got '800'" \
  "bad --size" frames "$TMP/pend.h5" --size 800 -o "$TMP/xframes"
fails 2 "sinew-plot: --fps is for movie, not frames" "--fps on frames" \
  frames "$TMP/pend.h5" --fps 10 -o "$TMP/xframes"
fails 2 "sinew-plot: --every is for frames, not movie" "--every on movie" \
  movie "$TMP/pend.h5" --every 10 -o "$TMP/x.mp4"
fails 2 "sinew-plot: --speed must be a positive number (1: real time)" "zero speed" \
  movie "$TMP/pend.h5" --speed 0 -o "$TMP/x.mp4"
fails 2 "sinew-plot: no output file: give -o OUT.mp4" "movie without -o" movie "$TMP/pend.h5"
fails 2 "sinew-plot: movie takes exactly one file" "movie of two files" \
  movie "$TMP/pend.h5" "$TMP/long.h5" -o "$TMP/x.mp4"
# Ctrl-C, as a terminal sends it (SIGINT to the foreground process group),
# 2 s into a movie of 12,000 frames: exit 130, one line, no partial movie,
# no ffmpeg left running
$PY - "$PLOT" "$TMP" <<'EOF' >"$TMP/measure" 2>"$TMP/log"
import os, signal, subprocess, sys, time
plot, d = sys.argv[1], sys.argv[2]
p = subprocess.Popen([plot, "movie", f"{d}/long.h5", "-o", f"{d}/x.mp4", "--size", "160x120",
                      "--fps", "30", "--speed", "0.05"],
                     stderr=subprocess.PIPE, start_new_session=True)
time.sleep(2)
os.killpg(p.pid, signal.SIGINT)
err = p.communicate(timeout=30)[1].decode().strip()
def cmdline(pid):
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as fh:
            return fh.read()
    except OSError:
        return b""
left = [p for p in os.listdir("/proc") if p.isdigit() and f"{d}/x.mp4".encode() in cmdline(p)]
print(p.returncode, int(os.path.exists(f"{d}/x.mp4")), int(bool(left)), err.replace("\n", " | "))
EOF
read -r rc partial running msg <"$TMP/measure"
[ "$rc" = 130 ] && [ "$partial" = 0 ] && [ "$running" = 0 ] && [ "$msg" = "sinew-plot: interrupted" ]
ok $? "Ctrl-C during a movie: exit $rc, \"$msg\", partial file $partial, ffmpeg left $running"
diag <"$TMP/log"
"$PLOT" movie "$TMP/pend.h5" --size 160x120 -o /nonexistent/x.mp4 >"$TMP/log" 2>&1
rc=$?
last=$(tail -n 1 "$TMP/log")
case $last in "sinew-plot: /nonexistent/x.mp4: cannot write the movie (ffmpeg: "*")") res=0 ;; *) res=1 ;; esac
[ $rc -eq 4 ] && [ $res -eq 0 ] && ! grep -q Traceback "$TMP/log"
ok $? "unwritable movie: exit 4, one line with ffmpeg's reason: $last"
done_testing
