/** The value after `--name` on the command line, or `dflt` when the option is absent (the stand-alone benchmark scripts' one option syntax). */
export function cliArg(name, dflt) {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 ? process.argv[i + 1] : dflt;
}
