// Compatibility shim: Debian bookworm's libocct-foundation-dev 7.6.3+dfsg1-7
// ships Poly_ArrayOfNodes.hxx, which includes this header, but not the header
// itself, so every file including BRep_Tool.hxx fails to compile. CMake adds
// this directory to the include path only when the system header is missing.
//
// Written from OCCT 7.6's documented interface: a contiguous array of
// fixed-stride elements viewed as different types. The data members keep the
// 7.6 order and types (pointer, stride, size, ownership flag) so classes that
// embed it (Poly_Triangulation) have the layout the shared libraries expect.
// Tessella itself never uses these arrays.
#ifndef TESSELLA_COMPAT_NCOLLECTION_ALIASEDARRAY_HXX
#define TESSELLA_COMPAT_NCOLLECTION_ALIASEDARRAY_HXX

#include <NCollection_DefineAlloc.hxx>
#include <Standard.hxx>
#include <Standard_DimensionMismatch.hxx>
#include <Standard_OutOfMemory.hxx>
#include <Standard_OutOfRange.hxx>
#include <Standard_TypeMismatch.hxx>

#include <cstring>
#include <utility>

template <int MyAlignSize = 16>
class NCollection_AliasedArray {
 public:
  DEFINE_STANDARD_ALLOC

  explicit NCollection_AliasedArray(Standard_Integer theStride)
      : myData(NULL), myStride(theStride), mySize(0), myToFree(false) {
    if (theStride <= 0) throw Standard_RangeError("NCollection_AliasedArray, stride must be > 0");
  }

  NCollection_AliasedArray(Standard_Integer theStride, Standard_Integer theLength)
      : myData(NULL), myStride(theStride), mySize(theLength), myToFree(true) {
    if (theLength <= 0 || myStride <= 0)
      throw Standard_RangeError("NCollection_AliasedArray, stride and length must be > 0");
    myData = allocate(SizeBytes());
  }

  NCollection_AliasedArray(const NCollection_AliasedArray& theOther)
      : myData(NULL), myStride(theOther.myStride), mySize(theOther.mySize), myToFree(false) {
    if (mySize != 0) {
      myToFree = true;
      myData = allocate(SizeBytes());
      std::memcpy(myData, theOther.myData, SizeBytes());
    }
  }

  NCollection_AliasedArray(NCollection_AliasedArray&& theOther)
      : myData(theOther.myData),
        myStride(theOther.myStride),
        mySize(theOther.mySize),
        myToFree(theOther.myToFree) {
    theOther.myToFree = false;
  }

  // Wraps existing memory without copying it.
  template <typename Type_t>
  NCollection_AliasedArray(const Type_t& theBegin, Standard_Integer theLength)
      : myData((Standard_Byte*)&theBegin),
        myStride((int)sizeof(Type_t)),
        mySize(theLength),
        myToFree(false) {
    if (theLength <= 0) throw Standard_RangeError("NCollection_AliasedArray, length must be > 0");
  }

  ~NCollection_AliasedArray() {
    if (myToFree) Standard::FreeAligned(myData);
  }

  Standard_Integer Stride() const { return myStride; }
  Standard_Integer Size() const { return mySize; }
  Standard_Integer Length() const { return mySize; }
  Standard_Boolean IsEmpty() const { return mySize == 0; }
  Standard_Integer Lower() const { return 0; }
  Standard_Integer Upper() const { return mySize - 1; }
  Standard_Boolean IsDeletable() const { return myToFree; }
  Standard_Boolean IsAllocated() const { return myToFree; }
  Standard_Size SizeBytes() const { return size_t(myStride) * size_t(mySize); }

  NCollection_AliasedArray& Assign(const NCollection_AliasedArray& theOther) {
    if (&theOther == this) return *this;
    if (myStride != theOther.myStride || SizeBytes() != theOther.SizeBytes() || theOther.myData == NULL)
      throw Standard_DimensionMismatch("NCollection_AliasedArray::Assign(), arrays have different size");
    if (myData != NULL) std::memcpy(myData, theOther.myData, SizeBytes());
    return *this;
  }

  NCollection_AliasedArray& Move(NCollection_AliasedArray& theOther) {
    if (&theOther == this) return *this;
    if (myToFree) Standard::FreeAligned(myData);
    myData = theOther.myData;
    myStride = theOther.myStride;
    mySize = theOther.mySize;
    myToFree = theOther.myToFree;
    theOther.myToFree = false;
    theOther.myData = NULL;
    theOther.mySize = 0;
    return *this;
  }

  NCollection_AliasedArray& operator=(const NCollection_AliasedArray& theOther) {
    return Assign(theOther);
  }
  NCollection_AliasedArray& operator=(NCollection_AliasedArray&& theOther) {
    return Move(theOther);
  }

  void Resize(Standard_Integer theLength, Standard_Boolean theToCopyData) {
    if (theLength <= 0) throw Standard_RangeError("NCollection_AliasedArray::Resize, length must be > 0");
    if (mySize == theLength) return;
    Standard_Byte* anOld = myData;
    const Standard_Integer anOldLen = mySize;
    const Standard_Boolean anOldOwned = myToFree;
    mySize = theLength;
    myToFree = true;
    myData = allocate(SizeBytes());
    if (theToCopyData && anOld != NULL) {
      const Standard_Integer aCount = anOldLen < theLength ? anOldLen : theLength;
      std::memcpy(myData, anOld, size_t(aCount) * size_t(myStride));
    }
    if (anOldOwned) Standard::FreeAligned(anOld);
  }

  const Standard_Byte* value(Standard_Integer theIndex) const {
    Standard_OutOfRange_Raise_if(theIndex < 0 || theIndex >= mySize, "NCollection_AliasedArray::value(), out of range index");
    return myData + size_t(myStride) * size_t(theIndex);
  }
  Standard_Byte* changeValue(Standard_Integer theIndex) {
    Standard_OutOfRange_Raise_if(theIndex < 0 || theIndex >= mySize, "NCollection_AliasedArray::changeValue(), out of range index");
    return myData + size_t(myStride) * size_t(theIndex);
  }

  template <typename Type_t>
  const Type_t& Value(Standard_Integer theIndex) const {
    Standard_TypeMismatch_Raise_if(size_t(myStride) != sizeof(Type_t), "NCollection_AliasedArray::Value(), wrong type");
    return *reinterpret_cast<const Type_t*>(value(theIndex));
  }
  template <typename Type_t>
  Type_t& ChangeValue(Standard_Integer theIndex) {
    Standard_TypeMismatch_Raise_if(size_t(myStride) != sizeof(Type_t), "NCollection_AliasedArray::ChangeValue(), wrong type");
    return *reinterpret_cast<Type_t*>(changeValue(theIndex));
  }
  template <typename Type_t>
  void SetValue(Standard_Integer theIndex, const Type_t& theItem) {
    ChangeValue<Type_t>(theIndex) = theItem;
  }
  template <typename Type_t>
  const Type_t& First() const { return Value<Type_t>(0); }
  template <typename Type_t>
  const Type_t& Last() const { return Value<Type_t>(mySize - 1); }

 private:
  static Standard_Byte* allocate(Standard_Size theBytes) {
    Standard_Byte* aData = (Standard_Byte*)Standard::AllocateAligned(theBytes, MyAlignSize);
    if (aData == NULL) throw Standard_OutOfMemory("NCollection_AliasedArray, allocation failed");
    return aData;
  }

 protected:
  Standard_Byte* myData;
  Standard_Integer myStride;
  Standard_Integer mySize;
  Standard_Boolean myToFree;
};

#endif
