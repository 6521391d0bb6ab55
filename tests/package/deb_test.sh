#!/usr/bin/env bash
# CTest check of the Debian package (label package; docs/packaging.md):
#
#   deb_test.sh SOURCE_DIR BUILD_DIR OUT_DIR
#
# Runs `cpack -G DEB` of BUILD_DIR into OUT_DIR and checks, with dpkg-deb, the file name, the
# files and their owner, the unit's paths, the control fields (Depends from dpkg-shlibdeps),
# conffiles and maintainer scripts; then that lintian (when installed) reports no error (E:).
# Exit 77 = skipped (CTest SKIP_RETURN_CODE): cpack, dpkg-deb or dpkg-shlibdeps is absent.
# The install, upgrade and purge in a chroot are scripts/package-check (network, minutes).
set -euo pipefail

source_dir=$1
build=$2
out=$3

fail() { echo "FAIL: $*" >&2; exit 1; }
for tool in cpack dpkg-deb dpkg-shlibdeps; do
  command -v "$tool" >/dev/null || { echo "SKIP: $tool not found (Debian package dpkg-dev)"; exit 77; }
done

rm -rf "$out" && mkdir -p "$out"
(cd "$build" && cpack -G DEB -B "$out" >"$out/cpack.log" 2>&1) || { cat "$out/cpack.log"; fail "cpack"; }
version=$(sed -n 's/^set(CPACK_PACKAGE_VERSION "\(.*\)")$/\1/p' "$build/CPackConfig.cmake")
release=$(sed -n 's/^set(CPACK_DEBIAN_PACKAGE_RELEASE "\(.*\)")$/\1/p' "$build/CPackConfig.cmake")
deb=$out/swlio_${version}-${release}_$(dpkg --print-architecture).deb
[[ -f $deb ]] || fail "no $deb: $(ls "$out")"
echo "$(basename "$deb"): $(stat -c %s "$deb") bytes"

# Files: every installed program with its man page, the systemd files, config, docs.
contents=$(dpkg-deb -c "$deb")
listed() { awk '{ print $6 }' <<<"$contents" | grep -qx "./$1" || fail "not in the package: $1"; }
programs=(swliod swlioctl swlio-replay)
[[ -f $source_dir/tools/report/swlio-report ]] && programs+=(swlio-report)
for program in "${programs[@]}"; do listed "usr/bin/$program"; done
while read -r path; do
  program=$(basename "$path")
  section=8 && [[ $program != swliod ]] && section=1
  listed "usr/share/man/man$section/$program.$section.gz"
done < <(awk '$6 ~ "^./usr/bin/." { print $6 }' <<<"$contents")
for path in usr/lib/systemd/system/swliod.service usr/lib/sysusers.d/swlio.conf \
  usr/lib/tmpfiles.d/swlio.conf usr/share/swlio/swliod-realtime.conf etc/swlio/swlio.yaml \
  usr/share/doc/swlio/copyright usr/share/doc/swlio/changelog.Debian.gz; do
  listed "$path"
done
not_root=$(awk '$2 != "root/root"' <<<"$contents")
[[ -z $not_root ]] || fail "files not owned by root: $not_root"

# The unit names the installed paths, not the staging tree.
dpkg-deb -x "$deb" "$out/tree"
exec_start=$(grep '^ExecStart=' "$out/tree/usr/lib/systemd/system/swliod.service")
[[ $exec_start == 'ExecStart=/usr/bin/swliod --config /etc/swlio/swlio.yaml' ]] ||
  fail "unit: $exec_start"
gzip -t "$out"/tree/usr/share/man/man*/*.gz || fail "a man page is not gzip"

# Control: fields, Depends from dpkg-shlibdeps, conffiles = every file under /etc.
field() { dpkg-deb -f "$deb" "$1"; }
[[ $(field Package) == swlio && $(field Version) == "$version-$release" ]] || fail "name/version"
for name in Maintainer Section Priority Description Installed-Size; do
  [[ -n $(field "$name") ]] || fail "no $name field"
done
field Depends | grep -q 'libc6 (>=' || fail "Depends lacks the shared libraries: $(field Depends)"
field Depends | grep -qw systemd || fail "Depends lacks systemd: $(field Depends)"
dpkg-deb -e "$deb" "$out/control"
want_conffiles=$(cd "$out/tree" && find etc -type f | sed 's|^|/|' | sort)
[[ $(sort "$out/control/conffiles") == "$want_conffiles" ]] ||
  fail "conffiles: $(cat "$out/control/conffiles") (want: $want_conffiles)"
for script in postinst prerm postrm; do
  [[ -x $out/control/$script ]] || fail "no executable $script"
  head -n1 "$out/control/$script" | grep -qx '#!/bin/sh' || fail "$script is not a /bin/sh script"
  grep -qx 'set -e' "$out/control/$script" || fail "$script lacks set -e"
  sh -n "$out/control/$script" || fail "$script: syntax"
done
# The service stays disabled and stopped after installing (the operator enables it).
! grep -v '^ *#' "$out/control/postinst" |
  grep -E 'systemctl (enable|start)|deb-systemd-helper enable|deb-systemd-invoke start' ||
  fail "postinst enables or starts the service"
grep -q 'systemd-sysusers swlio.conf' "$out/control/postinst" || fail "postinst makes no user"
grep -q 'deb-systemd-invoke stop swliod.service' "$out/control/prerm" || fail "prerm does not stop swliod"
echo "contents, control, conffiles ($(wc -l <"$out/control/conffiles")), maintainer scripts: OK"

if command -v lintian >/dev/null; then
  lintian_out=$(lintian --tag-display-limit 0 "$deb" 2>&1 | grep -v 'with root privileges') || true
  echo "lintian: ${lintian_out:-no tags}"
  ! grep -q '^E: ' <<<"$lintian_out" || fail "lintian reports errors"
else
  echo "lintian not installed: not run"
fi
