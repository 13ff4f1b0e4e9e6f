// Where the page gets an EPSG code's definition: crs/CODE.json beside the page (the dev server
// and the built site serve one per code: lib/crs_files_plugin.js), fetched only when a file names
// that code. A code with no file has no definition.

/** @returns {Promise<import('../geo/crs_definitions.js').CrsDefinition|null>} */
export async function fetchCrsDefinition(code) {
  const response = await fetch(new URL(`crs/${code}.json`, document.baseURI));
  if (response.status === 404) return null;
  if (!response.ok) throw new Error(`crs/${code}.json: HTTP ${response.status}`);
  return response.json();
}
