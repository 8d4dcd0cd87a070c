// A NIfTI-1 file (.nii) in memory: the format NiiVue loads. The voxels keep the card's layout (x fastest),
// and the sform maps voxel index to NiiVue's mm space.
const DATATYPE = { uint8: [2, 8], uint16: [512, 16], float32: [16, 32] };

// srow: three rows of four (mm = srow * (i, j, k, 1)); pixdim: the voxel size along i, j, k.
export function makeNifti(dims, voxelType, voxels, srow, pixdim) {
  const header = Buffer.alloc(352); // 348 bytes of header, then 4 bytes: no extension
  header.writeInt32LE(348, 0);
  [3, dims[0], dims[1], dims[2], 1, 1, 1, 1].forEach((d, i) => header.writeInt16LE(d, 40 + 2 * i));
  const [datatype, bitpix] = DATATYPE[voxelType];
  header.writeInt16LE(datatype, 70);
  header.writeInt16LE(bitpix, 72);
  [1, pixdim[0], pixdim[1], pixdim[2], 1, 1, 1, 1].forEach((p, i) => header.writeFloatLE(p, 76 + 4 * i));
  header.writeFloatLE(352, 108); // vox_offset
  header.writeFloatLE(1, 112); // scl_slope: values as stored
  header.writeFloatLE(0, 116); // scl_inter
  header.writeUInt8(2, 123); // xyzt_units: mm
  header.writeInt16LE(0, 252); // qform_code: unused
  header.writeInt16LE(1, 254); // sform_code: scanner coordinates
  srow.forEach((row, r) => row.forEach((v, c) => header.writeFloatLE(v, 280 + 16 * r + 4 * c)));
  header.write('n+1\0', 344, 'latin1');
  return Buffer.concat([header, voxels]);
}
