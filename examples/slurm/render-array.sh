#!/usr/bin/env bash
# A long full-quality flythrough split by frame range across a Slurm job array,
# then joined losslessly (ffmpeg's concat demuxer, no re-encoding).
#
#   sbatch examples/slurm/render-array.sh            # FRAMES, CHUNK, OUT and the terrain below
#
# Each task renders frames [i*CHUNK, min((i+1)*CHUNK, FRAMES)) of the same run
# into its own video (and stats JSON); a dependent job joins them into
# $OUT/flythrough.mp4. Full and voxel frames are bit-identical to a single run;
# LOD-sprite starts each range with a keyframe. Segment boundaries start new
# groups of pictures, so the joined video decodes within PSNR 40 dB of a
# single run's, not bit-identically.
#SBATCH --job-name=terrasprite-render
#SBATCH --array=0-9
#SBATCH --cpus-per-task=4
#SBATCH --time=02:00:00
#SBATCH --output=%x-%A_%a.log
set -euo pipefail

FRAMES=${FRAMES:-4600}
CHUNK=${CHUNK:-460}                  # frames per task: FRAMES / CHUNK tasks (--array=0-9 above)
OUT=${OUT:-$PWD/out/array}
TERRASPRITE=${TERRASPRITE:-terrasprite}
RENDER_ARGS=${RENDER_ARGS:---mode full --size 1920x1080 --path paper --fps 30 --preset veryfast}

join_segments() {
  local list="$OUT/segments.txt"
  : >"$list"
  for f in "$OUT"/segment_*.mp4; do echo "file '$f'" >>"$list"; done
  ffmpeg -v error -y -f concat -safe 0 -i "$list" -c copy "$OUT/flythrough.mp4.partial.mp4"
  mv "$OUT/flythrough.mp4.partial.mp4" "$OUT/flythrough.mp4"
  echo "joined $(wc -l <"$list") segments -> $OUT/flythrough.mp4"
}

if [ "${1:-}" = "--join" ]; then
  join_segments
  exit 0
fi

mkdir -p "$OUT"
i=${SLURM_ARRAY_TASK_ID:?run through sbatch (or set SLURM_ARRAY_TASK_ID)}
a=$((i * CHUNK))
b=$(((i + 1) * CHUNK))
[ "$b" -gt "$FRAMES" ] && b=$FRAMES
[ "$a" -lt "$b" ] || exit 0
seg=$(printf '%s/segment_%05d.mp4' "$OUT" "$i")
# shellcheck disable=SC2086
"$TERRASPRITE" render $RENDER_ARGS --frames "$FRAMES" --frame-range "$a:$b" \
  --video "$seg" --overwrite --json "$OUT/segment_$(printf '%05d' "$i").json"

# The last task to start submits the join once the whole array is done.
if [ "$i" -eq "${SLURM_ARRAY_TASK_MAX:-$i}" ]; then
  sbatch --dependency="afterok:${SLURM_ARRAY_JOB_ID}" --job-name=terrasprite-join \
    --wrap="OUT='$OUT' bash '$(readlink -f "$0")' --join"
fi
