#!/usr/bin/env bash
# CI: the README's two commands on a bare Debian bookworm.
#
# Makes a debootstrap --variant=minbase chroot, installs only git in it, clones this
# repository's HEAD (the committed state, never the working tree) with ../shared beside
# the clone, and runs there, as root without sudo:
#   1. ./scripts/setup.sh && ./build/gbxc solve specs/thruster_two_stage.gbx
#   2. ./scripts/setup.sh && ctest --test-dir build --output-on-failure -j2 -LE heavy
#      (the tests labelled `heavy` ran in the release suite already; what this run checks is
#      that a bare machine installs and builds everything they need)
# Fails unless both exit 0 and command 1 prints designs. Runs as root.
#
# The mirror is the one this machine's apt uses. The fresh minbase is cached as a tarball
# (GBX_BARE_CACHE, default /var/cache/gbx-bare-bookworm.tar; empty disables) so later
# runs skip debootstrap; the cache holds nothing but the minbase, so every run starts bare.
# GBX_BARE_KEEP=1 keeps the chroot directory for inspection (mounts are removed anyway).
# The machine's ccache folder is bound into the chroot (see below; GBX_BARE_CCACHE= leaves it).
set -euo pipefail

suite=bookworm
cache=${GBX_BARE_CACHE-/var/cache/gbx-bare-bookworm.tar}
cache_max_days=${GBX_BARE_CACHE_MAX_DAYS:-30}
work_parent=${GBX_BARE_DIR:-/var/tmp}

say() { printf '== bare-chroot: %s\n' "$*"; }
die() { printf 'bare-chroot: error: %s\n' "$*" >&2; exit 1; }

((EUID == 0)) || die "must run as root (debootstrap, mount, chroot)"

repo=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel) || die "not inside a git repository"
shared=$(cd "$repo/.." && pwd)/shared
[[ -d $shared ]] || die "no $shared: the repository expects ../shared beside it"
rev=$(git -C "$repo" rev-parse HEAD) || die "cannot resolve HEAD of $repo"

# The first URI of the machine's apt sources that serves $suite itself (not -updates or
# -security), deb822 .sources files first, then one-line .list files.
mirror_uri() {
  local f
  for f in /etc/apt/sources.list.d/*.sources; do
    [[ -f $f ]] || continue
    # Stanzas are separated by blank lines; keys are case-insensitive.
    awk -v suite="$suite" '
      function flush() {
        if (uri != "" && types ~ /(^|[ \t])deb([ \t]|$)/ && (" " suites " ") ~ ("[ \t]" suite "[ \t/]"))
          { print uri; found = 1; exit }
        uri = ""; types = ""; suites = ""
      }
      /^[ \t]*#/ { next }
      /^[ \t]*$/ { flush(); next }
      { key = tolower($1); sub(/:$/, "", key); $1 = "" ; val = $0; sub(/^[ \t]+/, "", val) }
      key == "uris"   { split(val, u, /[ \t]+/); uri = u[1] }
      key == "types"  { types = val }
      key == "suites" { suites = val }
      END { if (!found) flush() }
    ' "$f"
  done
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [[ -f $f ]] || continue
    # deb [options] URI SUITE COMPONENT...
    sed -E -e 's/#.*//' -e 's/\[[^]]*\]//' "$f" |
      awk -v suite="$suite" '$1 == "deb" && $3 == suite { print $2 }'
  done
}
mirror=$(mirror_uri | head -n1)
[[ -n $mirror ]] || die "no 'deb' source for $suite in /etc/apt/sources.list{,.d/*}"

root=
mounts=()
inside=
# The script's own stdout and stderr: a signal may arrive while they point at a log.
exec 8>&1 9>&2
cleanup() {
  local rc=$? i
  set +e
  exec 1>&8 2>&9
  if [[ -n $inside ]] && kill -0 "$inside" 2>/dev/null; then
    echo "bare-chroot: stopping what runs in the chroot" >&2
    kill -TERM -- "-$inside" 2>/dev/null
    for ((i = 0; i < 20; i++)); do kill -0 "$inside" 2>/dev/null || break; sleep 0.5; done
    kill -KILL -- "-$inside" 2>/dev/null
    wait "$inside" 2>/dev/null
  fi
  # Whatever left that group (apt runs dpkg in a group of its own) but still lives in the chroot.
  if [[ -n $root ]]; then
    rm -f "$root.debootstrap.log"
    [[ -z $cache ]] || rm -f "$cache.tmp.$$"
    for i in /proc/[0-9]*; do
      [[ $(readlink "$i/root" 2>/dev/null) == "$root" ]] && kill -KILL "${i#/proc/}" 2>/dev/null
    done
    sleep 0.5
  fi
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do
    umount "${mounts[i]}" 2>/dev/null || umount -l "${mounts[i]}" ||
      echo "bare-chroot: warning: could not unmount ${mounts[i]}" >&2
  done
  if [[ -n $root && -d $root ]]; then
    # Never delete through a mount that is still there (the repository, /dev, ...).
    if findmnt -rn -o TARGET | grep -q "^$root\(/\|$\)"; then
      echo "bare-chroot: warning: mounts remain under $root; not deleting it" >&2
    elif [[ ${GBX_BARE_KEEP:-} == 1 ]]; then
      echo "bare-chroot: kept $root"
    else
      rm -rf --one-file-system "$root"
    fi
  fi
  ((rc == 0)) || echo "bare-chroot: FAILED (exit $rc)" >&2
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

bind() { # bind SOURCE TARGET-IN-ROOT [ro]
  mkdir -p "$root$2"
  mount --bind "$1" "$root$2"
  mounts+=("$root$2")
  if [[ ${3:-} == ro ]]; then mount -o remount,bind,ro "$root$2"; fi
}

# Wall seconds of each step, for the summary.
declare -A took
t0=$SECONDS

if ! command -v debootstrap >/dev/null 2>&1; then
  say "installing debootstrap"
  DEBIAN_FRONTEND=noninteractive apt-get update -q
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q debootstrap
fi

root=$(mktemp -d "$work_parent/gbx-bare.XXXXXX")
root=$(realpath "$root")  # as /proc/*/root and findmnt spell it
chmod 755 "$root"

t=$SECONDS
if [[ -n $cache && -s $cache && -n $(find "$cache" -mtime -"$cache_max_days") ]] &&
   tar -xpf "$cache" -C "$root" 2>/dev/null && [[ -x $root/usr/bin/apt-get ]]; then
  say "minbase from the cache $cache"
else
  if [[ -n $cache && -e $cache ]]; then
    say "cache $cache is unusable or older than $cache_max_days days; making a new one"
    find "$root" -mindepth 1 -maxdepth 1 -exec rm -rf --one-file-system {} +
  fi
  say "debootstrap --variant=minbase $suite from $mirror"
  debootstrap --variant=minbase "$suite" "$root" "$mirror" > "$root.debootstrap.log" 2>&1 || {
    tail -n 30 "$root.debootstrap.log" >&2; rm -f "$root.debootstrap.log"; die "debootstrap failed"; }
  rm -f "$root.debootstrap.log"
  if [[ -n $cache ]]; then
    mkdir -p "$(dirname "$cache")"
    if ! { tar -cpf "$cache.tmp.$$" -C "$root" . && mv -f "$cache.tmp.$$" "$cache"; }; then
      rm -f "$cache.tmp.$$"; echo "bare-chroot: warning: could not write the cache $cache" >&2
    fi
  fi
fi
took[debootstrap]=$((SECONDS - t))

# What debootstrap writes, with today's mirror (the cache may predate a change of mirror).
echo "deb $mirror $suite main" > "$root/etc/apt/sources.list"
# Name resolution for apt inside.
if [[ -e /etc/resolv.conf ]]; then cp -L /etc/resolv.conf "$root/etc/resolv.conf"; fi
mkdir -p "$root/proc" "$root/sys" "$root/dev"
mount -t proc proc "$root/proc";  mounts+=("$root/proc")
mount -t sysfs sys "$root/sys";   mounts+=("$root/sys")
bind /dev /dev
bind /dev/pts /dev/pts
mount -t tmpfs -o mode=1777 shm "$root/dev/shm"; mounts+=("$root/dev/shm")
bind "$repo" /mnt/src ro

# Runs a command in the chroot in a clean environment: nothing from the host or the CI
# runner leaks in. In the background and a process group of its own, so that a signal to
# this script is handled at once (not after a build) and cleanup stops what runs inside.
in_root() {
  local rc=0
  setsid chroot "$root" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb CI=true \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin /bin/bash -c "$1" </dev/null &
  inside=$!
  wait "$inside" || rc=$?
  inside=
  return "$rc"
}

t=$SECONDS
say "installing git"
in_root 'export DEBIAN_FRONTEND=noninteractive
  apt-get update -q >/dev/null && apt-get install -y -q --no-install-recommends git >/dev/null' ||
  die "installing git in the chroot failed"
took[git]=$((SECONDS - t))

say "cloning $rev with ../shared beside it"
in_root "git -c safe.directory='*' clone -q --no-local /mnt/src /work/main && git -C /work/main -c advice.detachedHead=false checkout -q $rev" ||
  die "git clone in the chroot failed"
cp -a "$shared" "$root/work/shared"
umount "$root/mnt/src"; unset 'mounts[${#mounts[@]}-1]'
# The machine's compiler cache (scripts/ccache-launch), lent to the chroot: it serves only a
# compile whose every source and header is there and the same, so a package the bare
# machine lacks still fails the build; it spares recompiling what the release build just
# compiled. GBX_BARE_CCACHE= (empty) builds without it.
ccache_dir=${GBX_BARE_CCACHE-$(ccache -k cache_dir 2>/dev/null || true)}
if [[ -n $ccache_dir && -d $ccache_dir ]]; then
  say "compiler cache $ccache_dir lent to the chroot"
  bind "$ccache_dir" /root/.cache/ccache
fi

log=$root/work/readme-1.log
t=$SECONDS
say "README command 1: ./scripts/setup.sh && ./build/gbxc solve specs/thruster_two_stage.gbx"
if ! in_root 'cd /work/main && ./scripts/setup.sh && ./build/gbxc solve specs/thruster_two_stage.gbx' > "$log" 2>&1; then
  tail -n 60 "$log" >&2; cp "$log" "$root.readme-1.log"
  die "README command 1 failed in the bare chroot; whole log: $root.readme-1.log"
fi
took[command1]=$((SECONDS - t))
grep '^setup: ' "$log" || true
# The text report starts each gearbox with "gearbox NAME: N designs".
grep -Eq '^gearbox .+: [1-9][0-9]* designs?' "$log" || {
  tail -n 60 "$log" >&2; die "README command 1 exited 0 but printed no designs"; }
say "solve printed:"
grep -E '^gearbox ' "$log" | sed 's/^/    /'

log=$root/work/readme-2.log
t=$SECONDS
say "README command 2: ./scripts/setup.sh && ctest --test-dir build --output-on-failure -j2 -LE heavy"
if ! in_root 'cd /work/main && ./scripts/setup.sh && ctest --test-dir build --output-on-failure -j2 -LE heavy' > "$log" 2>&1; then
  tail -n 80 "$log" >&2; cp "$log" "$root.readme-2.log"
  die "README command 2 failed in the bare chroot; whole log: $root.readme-2.log"
fi
took[command2]=$((SECONDS - t))
grep -E 'tests passed|Total Test time' "$log" | sed 's/^/    /'
grep -q '100% tests passed' "$log" || die "README command 2 exited 0 but ctest did not report 100% passed"

times > "$root/work/times"  # not in $(...): a subshell's child times start at zero
cpu=$(tail -n1 "$root/work/times" | awk '{ print $1 " user + " $2 " sys" }')
say "passed; debootstrap ${took[debootstrap]}s, git ${took[git]}s, command 1 (packages + build + solve) ${took[command1]}s, command 2 ${took[command2]}s, total $((SECONDS - t0))s wall; CPU of children $cpu"
