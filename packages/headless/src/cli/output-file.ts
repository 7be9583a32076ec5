/**
 * vpt-render's output files: checked before anything is rendered (a folder, a device, a
 * read-only file or a folder that takes no new file would otherwise fail with a raw EISDIR or
 * EIO after the whole render), then written to a temporary file beside the target and renamed
 * over it, so a failed write never leaves a half-written image.
 */
import fs from 'node:fs';
import path from 'node:path';

function reason(e: unknown): string {
  const code = (e as NodeJS.ErrnoException).code;
  const words: Record<string, string> = {
    EACCES: 'permission denied',
    EPERM: 'not permitted',
    EROFS: 'read-only file system',
    ENOTDIR: 'a part of the path is a file, not a folder',
    ENOENT: 'the folder cannot be created there',
    EIO: 'input/output error',
  };
  return code && words[code] ? words[code] : (e as Error).message;
}

function temporaryBeside(file: string): string {
  return path.join(path.dirname(file), `.${path.basename(file)}.${process.pid}.vpt-render.tmp`);
}

/** Throws an Error naming `option` (e.g. "-o") unless `file` can be written as a new or replaced regular file. */
export function checkOutputFile(file: string, option: string): void {
  const target = path.resolve(file);
  const fail = (why: string): never => {
    throw new Error(`${option} ${file}: ${why}`);
  };
  let st: fs.Stats | undefined;
  try {
    st = fs.statSync(target);
  } catch {
    // Not there yet: fine, it will be created.
  }
  if (st?.isDirectory()) fail(`is a folder; name the image file (e.g. ${path.join(file, 'image.png')})`);
  if (st && !st.isFile()) fail('is not a regular file (a device or a pipe); name an image file');
  if (st) {
    try {
      fs.accessSync(target, fs.constants.W_OK);
    } catch (e) {
      fail(`cannot be overwritten: ${reason(e)}`);
    }
  }
  const dir = path.dirname(target);
  try {
    fs.mkdirSync(dir, { recursive: true });
  } catch (e) {
    fail(`its folder ${dir} cannot be created: ${reason(e)}`);
  }
  // The write goes through a new file in that folder (then a rename): try making one now.
  const probe = temporaryBeside(target);
  try {
    fs.closeSync(fs.openSync(probe, 'wx'));
    fs.rmSync(probe, { force: true });
  } catch (e) {
    fail(`cannot write in ${dir}: ${reason(e)}`);
  }
}

/** Write `data` to `file` through a temporary file beside it and a rename. */
export function writeOutputFile(file: string, data: Uint8Array, option: string): void {
  const target = path.resolve(file);
  const temporary = temporaryBeside(target);
  try {
    fs.mkdirSync(path.dirname(target), { recursive: true });
    fs.writeFileSync(temporary, data);
    fs.renameSync(temporary, target);
  } catch (e) {
    fs.rmSync(temporary, { force: true });
    throw new Error(`${option} ${file}: could not be written: ${reason(e)}`);
  }
}
