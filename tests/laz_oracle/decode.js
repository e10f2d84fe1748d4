// The independent oracle of the LAZ reader: laz-perf (LASzip's decoder
// compiled to WebAssembly, from npm) decodes a LAZ file and writes its raw
// point records, one after another, to OUTPUT.
// usage: node decode.js INPUT.laz OUTPUT.records
const fs = require('fs');
const { createLazPerf } = require('laz-perf');

async function main() {
  const [input, output] = process.argv.slice(2);
  const lazPerf = await createLazPerf();
  const file = fs.readFileSync(input);
  const filePointer = lazPerf._malloc(file.length);
  lazPerf.HEAPU8.set(file, filePointer);
  const laszip = new lazPerf.LASZip();
  laszip.open(filePointer, file.length);
  const count = laszip.getCount();
  const length = laszip.getPointLength();
  const pointPointer = lazPerf._malloc(length);
  const records = Buffer.alloc(count * length);
  const started = process.hrtime.bigint();
  for (let i = 0; i < count; ++i) {
    laszip.getPoint(pointPointer);
    records.set(lazPerf.HEAPU8.subarray(pointPointer, pointPointer + length), i * length);
  }
  const seconds = Number(process.hrtime.bigint() - started) / 1e9;
  fs.writeFileSync(output, records);
  laszip.delete();
  lazPerf._free(pointPointer);
  lazPerf._free(filePointer);
  process.stdout.write(JSON.stringify({ points: count, record_length: length, seconds }) + '\n');
}

main().catch((e) => { console.error(`decode.js: ${e && e.message ? e.message : e}`); process.exit(1); });
