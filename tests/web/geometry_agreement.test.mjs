// One block geometry per language, and they agree: the JavaScript volume and centroid
// (plugin/exchange/lib/rbla-geometry.mjs, which the viewer imports too) of the irregular blocks in
// tests/data/geometry/irregular_blocks.json equal those of the Python core, which wrote the file;
// tests/unit/test_geometry_agreement.cpp holds the solver to the same file.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { REPO, EXCHANGE, readJson } from './helpers.mjs';

const { polyhedronMassProps } = await import(path.join(EXCHANGE, 'lib', 'rbla-geometry.mjs'));

test('JavaScript and the Python core give the same volume and centroid', () => {
  const { blocks } = readJson(path.join(REPO, 'tests', 'data', 'geometry', 'irregular_blocks.json'));
  assert.ok(blocks.length >= 6);
  for (const b of blocks) {
    const { volume, centroid } = polyhedronMassProps(b.vertices, b.faces);
    assert.ok(Math.abs(volume - b.volume) <= 1e-12 * b.volume, `${b.id}: volume ${volume} against ${b.volume}`);
    const size = Math.cbrt(b.volume);  // the far block sits 1e3 m from the origin
    for (let i = 0; i < 3; i++) {
      assert.ok(Math.abs(centroid[i] - b.centroid[i]) <= 1e-10 * size,
                `${b.id}: centroid[${i}] ${centroid[i]} against ${b.centroid[i]}`);
    }
  }
});
