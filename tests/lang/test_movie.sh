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
#   movie    the same 0.3 s run as a movie: ffprobe counts its frames
#            against round(span x fps / speed) + 1 from the file's /time
#            (real time at 30 fps; --fps and --speed; the 300-frame cap on a
#            synthetic 20 s run), and reads its size, codec (h264 from
#            libx264, or mpeg4), rate and duration, printed as TAP comments
#   ffmpeg   not on PATH: the tool runs scripts/deps.sh beside itself (a
#            stand-in deps.sh records the call and puts ffmpeg on PATH,
#            and the movie is made), and says in one line, exit 1, what is
#            missing and how to get it when it may not install
#            (SINEW_NO_INSTALL=1; not root) or deps.sh leaves ffmpeg off
#            PATH (the installed copy, without deps.sh: test_install.sh)
#   errors   one line and the exit code for a file without rods, a missing
#            file, bad options, an unwritable movie; Ctrl-C exits 130 and
#            leaves neither a partial movie nor an ffmpeg
#
# ffmpeg is not one of `make test`'s base packages: this test installs it
# when it is missing (scripts/deps.sh ffmpeg:/usr/bin/ffmpeg, as test_paraview
# does for ParaView), so only a run of this test pulls it in; its absence
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
# probe FILE: "codec width height frames rate duration bytes" of the movie
probe() {
  ffprobe -v error -count_frames -select_streams v:0 \
    -show_entries stream=codec_name,width,height,nb_read_frames,r_frame_rate:format=duration,size \
    -of default=noprint_wrappers=1 "$1" |
    awk -F= '{ v[$1] = $2 } END { print v["codec_name"], v["width"], v["height"],
                                  v["nb_read_frames"], v["r_frame_rate"], v["duration"], v["size"] }'
}
# The frames a movie of the pendulum's run should have (sinew-plot's
# movie_frame_index): K = round(span x fps / speed) + 1, where span is the
# simulated time from the first of the F frames written to the last.
$PY - "$TMP/pend.h5" >"$TMP/span" 2>"$TMP/log" <<'EOF'
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    t = f["time"][()]
print(len(t), f"{t[-1] - t[0]:.6g}")
EOF
read -r nwritten span <"$TMP/span"
expect_frames() {   # expect_frames FPS SPEED: K
  awk -v s="$span" -v f="$1" -v v="$2" 'BEGIN { printf "%d\n", int(s * f / v + 0.5) + 1 }'
}
# movie DESCRIPTION EXPECTED ARGS...: exits 0 and ffprobe says EXPECTED
# ("width height frames rate"), the codec h264 or mpeg4, and a duration of
# frames / rate (to a frame); the figures are printed
movie() {
  what=$1 want=$2; shift 2
  rm -f "$TMP/out.mp4"
  "$PLOT" movie "$@" -o "$TMP/out.mp4" >"$TMP/log" 2>&1
  rc=$?
  probe "$TMP/out.mp4" >"$TMP/probe" 2>>"$TMP/log"
  read -r codec w h nframes rate dur bytes <"$TMP/probe"
  got="$w $h $nframes $rate"
  echo "# $what: ffprobe: $codec, ${w}x${h}, $nframes frames at $rate fps, $dur s, $bytes bytes"
  [ $rc -eq 0 ] && [ "$got" = "$want" ] && { [ "$codec" = h264 ] || [ "$codec" = mpeg4 ]; } &&
    awk -v d="$dur" -v k="$nframes" -v r="$rate" 'BEGIN { split(r, q, "/"); f = q[1] / q[2];
      e = d - k / f; if (e < 0) e = -e; exit !(e <= 1 / f) }'
  res=$?
  ok $res "$what: ffprobe says '$codec $got', $dur s"
  [ $res -eq 0 ] || { echo "exit $rc; expected '$want', h264 or mpeg4, $dur s = frames / rate"
                      cat "$TMP/log"; } | diag
}
k=$(expect_frames 30 1)
echo "# the pendulum wrote $nwritten frames over $span s: at 30 fps in real time," \
  "round($span x 30 / 1) + 1 = $k movie frames"
[ "$k" = 10 ]
ok $? "0.3 s of run at 30 fps is 9 intervals, 10 frames: $k"
diag <"$TMP/log"
mkdir "$TMP/tmpdir"
TMPDIR=$TMP/tmpdir movie "real time at 30 fps, $k frames" \
  "320 240 $k 30/1" "$TMP/pend.h5" --size 320x240
n=$(ls -A "$TMP/tmpdir" | wc -l)
[ "$n" -eq 0 ]
ok $? "the movie leaves no temporary file ($n in TMPDIR)"
k=$(expect_frames 20 0.5)
movie "--fps 20 --speed 0.5: 0.6 s of movie, round(0.3 x 20 / 0.5) + 1 = $k frames" \
  "640 480 $k 20/1" "$TMP/pend.h5" --fps 20 --speed 0.5 --size 640x480 --view 10,-80

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

# ---- ffmpeg not on PATH: an empty PATH hides it (the script's interpreter
# is absolute).  Where the tool may not install it: one line naming the
# package and the command, exit 1.
mkdir "$TMP/nobin"
RUN="env PATH=$TMP/nobin SINEW_NO_INSTALL=1"
fails 1 "sinew-plot: ffmpeg is missing and SINEW_NO_INSTALL forbids installing it: install Debian's ffmpeg package (apt-get install ffmpeg, as root)" \
  "movie without ffmpeg on PATH, SINEW_NO_INSTALL=1" movie "$TMP/pend.h5" -o "$TMP/x.mp4"
# (the installed sinew-plot, which has no deps.sh beside it: test_install.sh)
RUN="env PATH=$TMP/nobin"
if [ "$(id -u)" -eq 0 ]; then
  # as root the tool runs scripts/deps.sh, which finds Debian's ffmpeg
  # installed (above) and does nothing: ffmpeg is still off PATH
  fails 1 "sinew-plot: ffmpeg is not on PATH, though Debian's ffmpeg package is installed (/usr/bin/ffmpeg): add /usr/bin to PATH" \
    "movie without ffmpeg on PATH, as root: deps.sh runs, nothing to install" \
    movie "$TMP/pend.h5" -o "$TMP/x.mp4"
  # a stand-in deps.sh beside a copy of the script, reached through a
  # symlink: called with the package and its probe, it puts ffmpeg on PATH,
  # and the movie is made with it (the same 10 frames as the first movie)
  mkdir "$TMP/standin" "$TMP/link"
  cp "$PLOT" "$TMP/standin/sinew-plot"
  ln -s "$TMP/standin/sinew-plot" "$TMP/link/sinew-plot"
  cat >"$TMP/standin/deps.sh" <<'EOF'
# stand-in for scripts/deps.sh: records its arguments and "installs" ffmpeg
d=$(dirname "$0")
echo "$*" >>"$d/deps.args"
ln -s /usr/bin/ffmpeg "$d/ffmpeg"
EOF
  env PATH="$TMP/standin" "$TMP/link/sinew-plot" movie "$TMP/pend.h5" --size 160x120 \
    -o "$TMP/y.mp4" >"$TMP/log" 2>&1
  rc=$?
  called=$(cat "$TMP/standin/deps.args" 2>/dev/null)
  got=$(probe "$TMP/y.mp4" 2>>"$TMP/log" | cut -d' ' -f2-5)
  [ $rc -eq 0 ] && [ "$called" = "ffmpeg:/usr/bin/ffmpeg" ] &&
    [ "$got" = "160 120 $(expect_frames 30 1) 30/1" ]
  res=$?
  ok $res "movie without ffmpeg on PATH, as root: deps.sh beside the script is run with\
 '$called', then the movie is made ('$got')"
  [ $res -eq 0 ] || { echo "exit $rc"; cat "$TMP/log"; } | diag
else
  fails 1 "sinew-plot: ffmpeg is missing and only root can install it: install Debian's ffmpeg package (sudo apt-get install ffmpeg)" \
    "movie without ffmpeg on PATH, not root" movie "$TMP/pend.h5" -o "$TMP/x.mp4"
fi
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
# into a movie of 12,000 frames once its ffmpeg runs (on a loaded machine the
# imports alone may take seconds; a fixed delay then hit them): exit 130,
# one line, no partial movie, no ffmpeg left running
$PY - "$PLOT" "$TMP" <<'EOF' >"$TMP/measure" 2>"$TMP/log"
import os, signal, subprocess, sys, time
plot, d = sys.argv[1], sys.argv[2]
def cmdline(pid):
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as fh:
            return fh.read()
    except OSError:
        return b""
def encoding():
    return [q for q in os.listdir("/proc") if q.isdigit() and f"{d}/x.mp4".encode() in cmdline(q)
            and b"ffmpeg" in cmdline(q)]
p = subprocess.Popen([plot, "movie", f"{d}/long.h5", "-o", f"{d}/x.mp4", "--size", "160x120",
                      "--fps", "30", "--speed", "0.05"],
                     stderr=subprocess.PIPE, start_new_session=True,
                     # a shell's `cmd &` starts tests with SIGINT ignored, and
                     # Python then installs no KeyboardInterrupt handler
                     preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
deadline = time.time() + 120
while not encoding() and p.poll() is None and time.time() < deadline:
    time.sleep(0.05)
time.sleep(0.5)
os.killpg(p.pid, signal.SIGINT)
err = p.communicate(timeout=60)[1].decode().strip()
left = [q for q in os.listdir("/proc") if q.isdigit() and f"{d}/x.mp4".encode() in cmdline(q)]
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
