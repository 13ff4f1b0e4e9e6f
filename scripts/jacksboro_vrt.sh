# Sourced by the fixture scripts that start from the Jacksboro DEM (make_mosaic_fixtures.sh,
# make_cog_fixtures.sh), so both see the same samples at the same place.
# jacksboro_vrt PROJECT_DIR prints the raw float32 file tests/fixtures/jacksboro_fault.f32 as
# GDAL sees it: a VRT naming its layout and georeference (the bounds of jacksboro_fault.json are
# cell edges; 1/1200 degree cells).
jacksboro_vrt() {
  cat <<VRT
<VRTDataset rasterXSize="403" rasterYSize="344">
  <SRS>EPSG:4326</SRS>
  <GeoTransform>-84.41375, 0.000833333333333333333, 0, 36.73291666666667, 0, -0.000833333333333333333</GeoTransform>
  <VRTRasterBand dataType="Float32" band="1" subClass="VRTRawRasterBand">
    <SourceFilename relativeToVRT="0">$1/tests/fixtures/jacksboro_fault.f32</SourceFilename>
    <ImageOffset>0</ImageOffset><PixelOffset>4</PixelOffset><LineOffset>1612</LineOffset>
    <ByteOrder>LSB</ByteOrder>
  </VRTRasterBand>
</VRTDataset>
VRT
}
