// A Monte Carlo worker: flies samples [first, end) of the study and posts their lines of
// samples.csv a slice at a time.
"use strict";
importScripts("karman_wasm.js", "karman_web.js");

function wasmBytes() {
  const text = atob(KARMAN_WASM_BASE64);
  const bytes = new Uint8Array(text.length);
  for (let i = 0; i < text.length; i++) { bytes[i] = text.charCodeAt(i); }
  return bytes;
}

const ready = wasm_bindgen({ module_or_path: wasmBytes() });

onmessage = async (e) => {
  const job = e.data;
  try {
    await ready;
    const files = new wasm_bindgen.Files();
    for (const [name, bytes] of job.files) { files.add(name, bytes); }
    const study = new wasm_bindgen.Study(job.name, job.text, files, job.samples, job.seed);
    for (let i = job.first; i < job.end; i += job.slice) {
      const stop = Math.min(i + job.slice, job.end);
      postMessage({ type: "lines", first: i, lines: study.lines(i, stop), count: stop - i });
    }
    postMessage({ type: "done" });
  } catch (error) {
    postMessage({ type: "error", error: typeof error === "string" ? error : String(error) });
  }
};
