# Sourced by the scripts that loop over variants (image-hashes.sh, walk-tails.sh): the names
# `punctual render --help` lists under an option, read from the tables it prints, so a new method
# or filter is covered with no edit to a script. A variant line is indented 25 columns under its
# option's line. Needs $binary, the punctual executable.
variants() {  # OPTION: the names --help lists under it
  "$binary" render --help | awk -v option="  $1 " '
    !done && index($0, option) == 1 { listing = 1; next }
    listing && /^  --/ { listing = 0; done = 1 }  # read on: an early exit would break the pipe
    listing && substr($0, 1, 25) ~ /^ +$/ && substr($0, 26, 1) != " " { print $1 }'
}
